// Engine-owned materials: metallic-roughness, the glass extensions the refraction plugin reads
// (transmission, volume, ior, dispersion) and the layers over the base every shading path
// follows (specular, clearcoat, sheen, iridescence, anisotropy, emissive strength).
#pragma once

#include <glm/glm.hpp>

#include <cmath>
#include <limits>
#include <string>

namespace scene {

/** KHR_texture_transform's offset, rotation (radians, counter-clockwise in UV space) and
 *  scale. */
struct UvTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;
    glm::vec2 scale{1.0f};
    /** translation * rotation * scale, as the extension composes them. */
    glm::mat3 matrix() const {
        const float c = std::cos(rotation), s = std::sin(rotation);
        return glm::mat3(c * scale.x, -s * scale.x, 0.0f, s * scale.y, c * scale.y, 0.0f, offset.x,
                         offset.y, 1.0f);
    }
};

/** A texture reference; texture == -1 means none. `scale` is the normal scale or occlusion
 *  strength where the slot has one. `transform` maps the mesh's texture coordinates to the
 *  texture's: `uv`'s matrix, identity without KHR_texture_transform (setUv() keeps the two in
 *  step). */
struct TextureRef {
    int texture = -1;
    int texCoord = 0;
    float scale = 1.0f;
    UvTransform uv{};
    glm::mat3 transform{1.0f};
    bool present() const { return texture >= 0; }
    glm::vec2 apply(glm::vec2 at) const { return glm::vec2(transform * glm::vec3(at, 1.0f)); }
    void setUv(const UvTransform& t) {
        uv = t;
        transform = t.matrix();
    }
};

enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    TextureRef baseColorTexture;
    float metallicFactor = 1.0f;
    float roughnessFactor = 1.0f;
    TextureRef metallicRoughnessTexture;
    TextureRef normalTexture;
    TextureRef occlusionTexture;
    TextureRef emissiveTexture;
    glm::vec3 emissiveFactor{0.0f};
    float emissiveStrength = 1.0f; ///< KHR_materials_emissive_strength
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    /** KHR_materials_unlit: the base colour is the colour, no lighting. */
    bool unlit = false;

    // KHR_materials_transmission
    bool hasTransmission = false;
    float transmissionFactor = 0.0f;
    TextureRef transmissionTexture;
    // KHR_materials_volume
    bool hasVolume = false;
    float thicknessFactor = 0.0f; ///< authored thickness in mesh units (the plugin derives its own)
    TextureRef thicknessTexture;
    float attenuationDistance = std::numeric_limits<float>::infinity(); ///< world units
    glm::vec3 attenuationColor{1.0f};
    // KHR_materials_ior
    bool hasIor = false;
    float ior = 1.5f;
    // KHR_materials_specular: the dielectric's specular weight (alpha of its texture) and its
    // F0's colour (rgb of its texture, sRGB)
    bool hasSpecular = false;
    float specularFactor = 1.0f;
    TextureRef specularTexture;
    glm::vec3 specularColorFactor{1.0f};
    TextureRef specularColorTexture;
    // KHR_materials_clearcoat: a second, colourless specular layer (F0 0.04) over the base, its
    // strength (texture r), roughness (texture g) and own normal map
    bool hasClearcoat = false;
    float clearcoatFactor = 0.0f;
    TextureRef clearcoatTexture;
    float clearcoatRoughnessFactor = 0.0f;
    TextureRef clearcoatRoughnessTexture;
    TextureRef clearcoatNormalTexture;
    // KHR_materials_sheen: a cloth-like retro-reflective layer, its colour (texture rgb, sRGB)
    // and roughness (texture alpha)
    bool hasSheen = false;
    glm::vec3 sheenColorFactor{0.0f};
    TextureRef sheenColorTexture;
    float sheenRoughnessFactor = 0.0f;
    TextureRef sheenRoughnessTexture;
    // KHR_materials_iridescence: a thin film on the surface, its strength (texture r), index of
    // refraction and thickness in nanometres (between minimum and maximum by texture g; the
    // maximum without a texture)
    bool hasIridescence = false;
    float iridescenceFactor = 0.0f;
    TextureRef iridescenceTexture;
    float iridescenceIor = 1.3f;
    float iridescenceThicknessMinimum = 100.0f;
    float iridescenceThicknessMaximum = 400.0f;
    TextureRef iridescenceThicknessTexture;
    // KHR_materials_anisotropy: the specular lobe stretched along a direction in the tangent
    // plane, `anisotropyRotation` radians from the tangent (texture rg: direction, b: strength)
    bool hasAnisotropy = false;
    float anisotropyStrength = 0.0f;
    float anisotropyRotation = 0.0f;
    TextureRef anisotropyTexture;
    // KHR_materials_dispersion: 20 / Abbe number
    bool hasDispersion = false;
    float dispersion = 0.0f;

    /** The dielectric's reflectance at normal incidence before KHR_materials_specular's colour:
     *  0.04 in glTF's core model, from the index of refraction with KHR_materials_ior. */
    float dielectricF0() const {
        if (!hasIor || ior < 1.0f)
            return 0.04f;
        const float r = (ior - 1.0f) / (ior + 1.0f);
        return r * r;
    }

    /** Every texture slot, with whether its texture holds colour (sRGB) rather than data. */
    template <typename F> void forEachTexture(F&& f) const {
        for (const TextureRef* t :
             {&baseColorTexture, &emissiveTexture, &specularColorTexture, &sheenColorTexture})
            f(*t, true);
        for (const TextureRef* t :
             {&metallicRoughnessTexture, &normalTexture, &occlusionTexture, &transmissionTexture,
              &thicknessTexture, &specularTexture, &clearcoatTexture, &clearcoatRoughnessTexture,
              &clearcoatNormalTexture, &sheenRoughnessTexture, &iridescenceTexture,
              &iridescenceThicknessTexture, &anisotropyTexture})
            f(*t, false);
    }

    /** The layers a material can put on its base: common/brdf.glsl's SURFACE_LAYERS bits (the
     *  shaders' LAYER_* defines, render/Shared.h). */
    static constexpr int kClearcoatLayer = 1, kSheenLayer = 2, kIridescenceLayer = 4,
                         kAnisotropyLayer = 8;
    /** The layers it puts on its base: the shader variant that shades it. */
    int surfaceLayers() const {
        return (hasClearcoat && clearcoatFactor > 0.0f ? kClearcoatLayer : 0) |
               (hasSheen && glm::max(sheenColorFactor.r,
                                     glm::max(sheenColorFactor.g, sheenColorFactor.b)) > 0.0f
                    ? kSheenLayer
                    : 0) |
               (hasIridescence && iridescenceFactor > 0.0f ? kIridescenceLayer : 0) |
               (hasAnisotropy && anisotropyStrength > 0.0f ? kAnisotropyLayer : 0);
    }

    /** Glass as the plugin sees it: any transmission. */
    bool isTransmissive() const { return hasTransmission && transmissionFactor > 0.0f; }
};

/** A material's texture slot: its path in a glTF material (as KHR_animation_pointer names it)
 *  and its member. */
struct TextureSlot {
    const char* path;
    TextureRef Material::*ref;
};

/** Every texture slot, in the order AnimationChannel::slot indexes them. */
inline constexpr TextureSlot kTextureSlots[] = {
    {"pbrMetallicRoughness/baseColorTexture", &Material::baseColorTexture},
    {"pbrMetallicRoughness/metallicRoughnessTexture", &Material::metallicRoughnessTexture},
    {"normalTexture", &Material::normalTexture},
    {"occlusionTexture", &Material::occlusionTexture},
    {"emissiveTexture", &Material::emissiveTexture},
    {"extensions/KHR_materials_transmission/transmissionTexture", &Material::transmissionTexture},
    {"extensions/KHR_materials_volume/thicknessTexture", &Material::thicknessTexture},
    {"extensions/KHR_materials_specular/specularTexture", &Material::specularTexture},
    {"extensions/KHR_materials_specular/specularColorTexture", &Material::specularColorTexture},
    {"extensions/KHR_materials_clearcoat/clearcoatTexture", &Material::clearcoatTexture},
    {"extensions/KHR_materials_clearcoat/clearcoatRoughnessTexture",
     &Material::clearcoatRoughnessTexture},
    {"extensions/KHR_materials_clearcoat/clearcoatNormalTexture",
     &Material::clearcoatNormalTexture},
    {"extensions/KHR_materials_sheen/sheenColorTexture", &Material::sheenColorTexture},
    {"extensions/KHR_materials_sheen/sheenRoughnessTexture", &Material::sheenRoughnessTexture},
    {"extensions/KHR_materials_iridescence/iridescenceTexture", &Material::iridescenceTexture},
    {"extensions/KHR_materials_iridescence/iridescenceThicknessTexture",
     &Material::iridescenceThicknessTexture},
    {"extensions/KHR_materials_anisotropy/anisotropyTexture", &Material::anisotropyTexture},
};

} // namespace scene
