// Front faces of the glass, the papers' second geometry pass: shades each fragment in front of
// the opaque scene (glass_shading.glsl).
#include "refraction/glass_shading.glsl"
#include "refraction/glass_inputs.glsl"

out vec4 outColor;

void main() {
    // Depth test against the opaque scene (sampled: its depth is not this pass's attachment).
    if (gl_FragCoord.z > texelFetch(uSceneDepth, ivec2(gl_FragCoord.xy), 0).r)
        discard;
    gNormalDistance = vNormalDistance;
    outColor = vec4(shadeGlass(vViewPosition, vViewNormal, vViewTangent, vUv), 1.0);
}
