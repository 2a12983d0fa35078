// After the single geometry pass: shades the pixels whose nearest glass surface lies in front of
// the opaque scene (glass_shading.glsl) over the scene colour copied before it; the resolve
// pass's depth mask keeps every other pixel of the glass rectangle from running this shader.
// The entry point comes back from the exact front depth, the normal and d_N from their keys.
#include "refraction/glass_shading.glsl"
#include "refraction/surfaces.glsl"

uniform sampler2D uGatherFar; // uBackDepth is the gathered near target (back depth in .r)
uniform mat4 uInverseProjection;

out vec4 outColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 near = texelFetch(uBackDepth, p, 0);
    float z = -near.y;
    vec4 ray = uInverseProjection * vec4(gl_FragCoord.xy / uViewportSize * 2.0 - 1.0, 1.0, 1.0);
    vec3 direction = ray.xyz / ray.w;
    vec3 P1 = direction * (z / -direction.z);
    uint d = keyPayload(texelFetch(uGatherFar, p, 0).z);
    gNormalDistance = d == 0u ? -1.0 : float(d - 1u) / 1022.0 * z;
    outColor = vec4(shadeGlass(P1, octDecodePayload(near.z, near.w), vec4(1.0, 0.0, 0.0, 1.0),
                               vec4(0.0)), 1.0);
}
