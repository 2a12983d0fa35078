// Opaque metallic-roughness surface lit by the environment (glTF core material model).
#include "common/brdf.glsl"
#include "common/normal_map.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;
in vec4 vWorldTangent;
in vec2 vUv;
out vec4 outColor;

uniform vec3 uCameraPosition;
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform vec3 uEmissive; // factor * strength
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform int uHasBaseColorTexture, uHasMetallicRoughnessTexture, uHasNormalTexture;
uniform int uHasOcclusionTexture, uHasEmissiveTexture;
uniform sampler2D uBaseColorTexture, uMetallicRoughnessTexture, uNormalTexture;
uniform sampler2D uOcclusionTexture, uEmissiveTexture;
// KHR_texture_transform of each slot (identity without it)
uniform mat3 uBaseColorUv, uMetallicRoughnessUv, uNormalUv, uOcclusionUv, uEmissiveUv;
uniform int uUnlit; // KHR_materials_unlit: the base colour, unshaded

vec2 uvOf(mat3 transform) {
    return (transform * vec3(vUv, 1.0)).xy;
}

void main() {
    vec4 baseColor = uBaseColorFactor;
    if (uHasBaseColorTexture != 0)
        baseColor *= texture(uBaseColorTexture, uvOf(uBaseColorUv)); // sRGB: decoded to linear
    if (uUnlit != 0) {
        outColor = vec4(baseColor.rgb, 1.0);
        return;
    }
    float metallic = uMetallicFactor, roughness = uRoughnessFactor;
    if (uHasMetallicRoughnessTexture != 0) {
        vec4 mr = texture(uMetallicRoughnessTexture, uvOf(uMetallicRoughnessUv));
        roughness *= mr.g;
        metallic *= mr.b;
    }
    vec3 N = normalize(vWorldNormal);
    vec3 V = normalize(uCameraPosition - vWorldPosition);
    if (!gl_FrontFacing)
        N = -N;
    if (uHasNormalTexture != 0)
        N = perturbNormal(N, vWorldTangent, uNormalTexture, uvOf(uNormalUv), uNormalScale);
    float occlusion = 1.0;
    if (uHasOcclusionTexture != 0)
        occlusion =
            mix(1.0, texture(uOcclusionTexture, uvOf(uOcclusionUv)).r, uOcclusionStrength);
    vec3 color = shadeMetallicRoughness(baseColor.rgb, clamp(metallic, 0.0, 1.0),
                                        clamp(roughness, 0.03, 1.0), occlusion, N, V);
    vec3 emissive = uEmissive;
    if (uHasEmissiveTexture != 0)
        emissive *= texture(uEmissiveTexture, uvOf(uEmissiveUv)).rgb;
    outColor = vec4(color + emissive, 1.0);
}
