// Opaque surfaces: glTF's material model with its extensions' layers (common/brdf.glsl), lit by
// the environment and the punctual lights; compiled per set of layers (SURFACE_LAYERS). Where the
// frame accumulates (uWriteMotion), each fragment's motion too (common/motion.glsl).
// DEFERRED (a material without layers): the surface's material into the surface targets and its
// emitted light into the colour, for the lighting pass to shade (common/surface_targets.glsl).
#ifndef DEFERRED
#define DEFERRED 0
#endif
#include "common/brdf.glsl"
#include "common/material_uv.glsl"
#include "common/motion.glsl"
#include "common/normal_map.glsl"
#if DEFERRED
#include "common/surface_targets.glsl"
#else
#define MOTION_TARGET 1
#endif

in vec3 vWorldPosition;
in vec3 vWorldNormal;
in vec4 vWorldTangent;
in vec4 vUv; // TEXCOORD_0 in xy, TEXCOORD_1 in zw
in vec4 vClip, vPreviousClip;
layout(location = 0) out vec4 outColor;
layout(location = MOTION_TARGET) out uvec4 outMotion;
uniform int uMotionObject; // the draw item's index + 1

uniform vec3 uCameraPosition;
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform vec3 uEmissive; // factor * strength
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform int uUnlit; // KHR_materials_unlit: the base colour, unshaded
// KHR_materials_specular: weight (factor, texture alpha) and F0 colour (factor, texture rgb)
uniform float uSpecularFactor, uDielectricF0;
uniform vec3 uSpecularColorFactor;
// KHR_materials_clearcoat, _sheen, _iridescence, _anisotropy (MaterialTextures::bind)
uniform float uClearcoatFactor, uClearcoatRoughnessFactor, uClearcoatNormalScale;
uniform vec3 uSheenColorFactor;
uniform float uSheenRoughnessFactor;
uniform float uIridescenceFactor, uIridescenceIor;
uniform vec2 uIridescenceThickness; // minimum, maximum (nm)
uniform float uAnisotropyStrength;
uniform vec2 uAnisotropyRotation; // cos, sin

bool has(int slot) {
    return hasTexture(slot);
}

vec4 read(int slot) {
    return readTexture(slot, vUv);
}

void main() {
    if (writesMotion())
        outMotion = packMotion(motionIdentity(MOTION_OPAQUE, uint(uMotionObject)),
                               clipToPixel(vClip) - clipToPixel(vPreviousClip), vClip.w,
                               vPreviousClip.w, 0u);
    vec4 baseColor = uBaseColorFactor;
    if (has(SLOT_BASE_COLOR))
        baseColor *= read(SLOT_BASE_COLOR); // sRGB: decoded to linear
    if (uUnlit != 0) {
        outColor = vec4(baseColor.rgb, 1.0);
#if DEFERRED // a surface that reflects nothing: the lighting adds zero
        SurfaceMaterial none = coreSurface(vec3(0.0), 0.0, 1.0, 0.0, vWorldNormal);
        none.dielectricF0 = vec3(0.0);
        none.specularWeight = 0.0;
        writeSurface(vWorldPosition, normalize(vWorldNormal), none);
#endif
        return;
    }
    float metallic = uMetallicFactor, roughness = uRoughnessFactor;
    if (has(SLOT_METALLIC_ROUGHNESS)) {
        vec4 mr = read(SLOT_METALLIC_ROUGHNESS);
        roughness *= mr.g;
        metallic *= mr.b;
    }
    vec3 geometric = normalize(vWorldNormal);
    vec3 V = normalize(uCameraPosition - vWorldPosition);
    if (!gl_FrontFacing)
        geometric = -geometric;
    vec3 N = geometric;
    if (has(SLOT_NORMAL))
        N = perturbNormal(N, vWorldTangent, uTexture[SLOT_NORMAL],
                          slotUv(vUv, SLOT_NORMAL), uNormalScale);
    float occlusion = 1.0;
    if (has(SLOT_OCCLUSION))
        occlusion = mix(1.0, read(SLOT_OCCLUSION).r, uOcclusionStrength);
    SurfaceMaterial m = coreSurface(baseColor.rgb, clamp(metallic, 0.0, 1.0),
                                    clamp(roughness, 0.03, 1.0), occlusion, geometric);
    // Each texture is read inside an if of its own: a ternary would have the compiler sample
    // every slot's texture for every pixel.
    m.specularWeight = uSpecularFactor;
    if (has(SLOT_SPECULAR))
        m.specularWeight *= read(SLOT_SPECULAR).a;
    m.dielectricF0 = uDielectricF0 * uSpecularColorFactor;
    if (has(SLOT_SPECULAR_COLOR))
        m.dielectricF0 *= read(SLOT_SPECULAR_COLOR).rgb;
#if (SURFACE_LAYERS & LAYER_CLEARCOAT) != 0
    if (uClearcoatFactor > 0.0) {
        m.clearcoat = uClearcoatFactor;
        if (has(SLOT_CLEARCOAT))
            m.clearcoat *= read(SLOT_CLEARCOAT).r;
        m.clearcoatRoughness = uClearcoatRoughnessFactor;
        if (has(SLOT_CLEARCOAT_ROUGHNESS))
            m.clearcoatRoughness *= read(SLOT_CLEARCOAT_ROUGHNESS).g;
        m.clearcoatRoughness = clamp(m.clearcoatRoughness, 0.03, 1.0);
        if (has(SLOT_CLEARCOAT_NORMAL))
            m.clearcoatNormal = perturbNormal(geometric, vWorldTangent, uTexture[SLOT_CLEARCOAT_NORMAL],
                                              slotUv(vUv, SLOT_CLEARCOAT_NORMAL), uClearcoatNormalScale);
    }
#endif
#if (SURFACE_LAYERS & LAYER_SHEEN) != 0
    if (max(uSheenColorFactor.r, max(uSheenColorFactor.g, uSheenColorFactor.b)) > 0.0) {
        m.sheenColor = uSheenColorFactor;
        if (has(SLOT_SHEEN_COLOR))
            m.sheenColor *= read(SLOT_SHEEN_COLOR).rgb;
        m.sheenRoughness = uSheenRoughnessFactor;
        if (has(SLOT_SHEEN_ROUGHNESS))
            m.sheenRoughness *= read(SLOT_SHEEN_ROUGHNESS).a;
    }
#endif
#if (SURFACE_LAYERS & LAYER_IRIDESCENCE) != 0
    if (uIridescenceFactor > 0.0) {
        m.iridescence = uIridescenceFactor;
        if (has(SLOT_IRIDESCENCE))
            m.iridescence *= read(SLOT_IRIDESCENCE).r;
        m.iridescenceIor = uIridescenceIor;
        m.iridescenceThickness = uIridescenceThickness.y;
        if (has(SLOT_IRIDESCENCE_THICKNESS))
            m.iridescenceThickness = mix(uIridescenceThickness.x, uIridescenceThickness.y,
                                         read(SLOT_IRIDESCENCE_THICKNESS).g);
    }
#endif
#if (SURFACE_LAYERS & LAYER_ANISOTROPY) != 0
    if (uAnisotropyStrength > 0.0) {
        // The texture's direction (rg in [-1, 1], tangent space) turned by the rotation, its
        // strength (b) times the factor.
        vec3 a = vec3(1.0, 0.5, 1.0);
        if (has(SLOT_ANISOTROPY))
            a = read(SLOT_ANISOTROPY).rgb;
        vec2 d = a.rg * 2.0 - 1.0;
        d = vec2(uAnisotropyRotation.x * d.x - uAnisotropyRotation.y * d.y,
                 uAnisotropyRotation.y * d.x + uAnisotropyRotation.x * d.y);
        vec3 T = normalize(vWorldTangent.xyz - N * dot(N, vWorldTangent.xyz));
        vec3 B = cross(N, T) * vWorldTangent.w;
        vec3 direction = T * d.x + B * d.y;
        if (dot(direction, direction) > 1e-8) {
            m.anisotropy = clamp(uAnisotropyStrength * a.b, 0.0, 1.0);
            m.anisotropyDirection = normalize(direction);
        }
    }
#endif
    vec3 emissive = uEmissive;
    if (has(SLOT_EMISSIVE))
        emissive *= read(SLOT_EMISSIVE).rgb;
#if DEFERRED
    writeSurface(vWorldPosition, N, m);
    outColor = vec4(emissive, 1.0);
#else
    outColor = vec4(shadeSurface(m, vWorldPosition, N, V) + emissive, 1.0);
#endif
}
