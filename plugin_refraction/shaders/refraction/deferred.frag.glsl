// After the single geometry pass: one full-screen pass shades the pixels whose nearest glass
// surface lies in front of the opaque scene (glass_shading.glsl) over the scene colour the
// resolve pass copied; the resolve pass's depth mask keeps every other pixel from running this
// shader. The entry point comes back from the exact front depth.
#include "refraction/glass_shading.glsl"

uniform mat4 uInverseProjection;

out vec4 outColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 front = texelFetch(uFrontDepth, p, 0).rg;
    vec4 ray = uInverseProjection * vec4(gl_FragCoord.xy / uViewportSize * 2.0 - 1.0, 1.0, 1.0);
    vec3 direction = ray.xyz / ray.w;
    vec3 P1 = direction * (front.r / -direction.z);
    gNormalDistance = front.g;
    vec3 N = texelFetch(uFrontNormal, p, 0).xyz;
    outColor = vec4(shadeGlass(P1, N, vec4(1.0, 0.0, 0.0, 1.0), vec2(0.0)), 1.0);
}
