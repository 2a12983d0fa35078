// Opaque metallic-roughness surface lit by the environment (glTF core material model).
#include "common/brdf.glsl"
#include "common/material_uv.glsl"
#include "common/normal_map.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;
in vec4 vWorldTangent;
in vec4 vUv; // TEXCOORD_0 in xy, TEXCOORD_1 in zw
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
// KHR_materials_specular: weight (factor, texture alpha) and F0 colour (factor, texture rgb)
uniform float uSpecularFactor, uDielectricF0;
uniform vec3 uSpecularColorFactor;
uniform int uHasSpecularTexture, uHasSpecularColorTexture;
uniform sampler2D uSpecularTexture, uSpecularColorTexture;
uniform mat3 uSpecularUv, uSpecularColorUv;


void main() {
    vec4 baseColor = uBaseColorFactor;
    if (uHasBaseColorTexture != 0)
        baseColor *= texture(uBaseColorTexture, slotUv(vUv, uBaseColorUv, SLOT_BASE_COLOR)); // sRGB: decoded to linear
    if (uUnlit != 0) {
        outColor = vec4(baseColor.rgb, 1.0);
        return;
    }
    float metallic = uMetallicFactor, roughness = uRoughnessFactor;
    if (uHasMetallicRoughnessTexture != 0) {
        vec4 mr = texture(uMetallicRoughnessTexture, slotUv(vUv, uMetallicRoughnessUv, SLOT_METALLIC_ROUGHNESS));
        roughness *= mr.g;
        metallic *= mr.b;
    }
    vec3 N = normalize(vWorldNormal);
    vec3 V = normalize(uCameraPosition - vWorldPosition);
    if (!gl_FrontFacing)
        N = -N;
    if (uHasNormalTexture != 0)
        N = perturbNormal(N, vWorldTangent, uNormalTexture, slotUv(vUv, uNormalUv, SLOT_NORMAL), uNormalScale);
    float occlusion = 1.0;
    if (uHasOcclusionTexture != 0)
        occlusion =
            mix(1.0, texture(uOcclusionTexture, slotUv(vUv, uOcclusionUv, SLOT_OCCLUSION)).r, uOcclusionStrength);
    float specularWeight = uSpecularFactor;
    if (uHasSpecularTexture != 0)
        specularWeight *= texture(uSpecularTexture, slotUv(vUv, uSpecularUv, SLOT_SPECULAR)).a;
    vec3 specularColor = uSpecularColorFactor;
    if (uHasSpecularColorTexture != 0)
        specularColor *=
            texture(uSpecularColorTexture, slotUv(vUv, uSpecularColorUv, SLOT_SPECULAR_COLOR)).rgb;
    vec3 color = shadeMetallicRoughnessSpecular(baseColor.rgb, clamp(metallic, 0.0, 1.0),
                                                clamp(roughness, 0.03, 1.0), occlusion, N, V,
                                                uDielectricF0 * specularColor, specularWeight);
    vec3 emissive = uEmissive;
    if (uHasEmissiveTexture != 0)
        emissive *= texture(uEmissiveTexture, slotUv(vUv, uEmissiveUv, SLOT_EMISSIVE)).rgb;
    outColor = vec4(color + emissive, 1.0);
}
