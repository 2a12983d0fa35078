// Engine-owned materials: metallic-roughness plus the glass extensions the refraction plugin
// reads (transmission, volume, ior, dispersion) and emissive strength.
#pragma once

#include <glm/glm.hpp>

#include <limits>
#include <string>

namespace scene {

/** A texture reference; texture == -1 means none. `scale` is the normal scale or occlusion
 *  strength where the slot has one. `transform` maps the mesh's texture coordinates to the
 *  texture's (KHR_texture_transform: translation * rotation * scale, identity without it). */
struct TextureRef {
    int texture = -1;
    int texCoord = 0;
    float scale = 1.0f;
    glm::mat3 transform{1.0f};
    bool present() const { return texture >= 0; }
    glm::vec2 apply(glm::vec2 uv) const { return glm::vec2(transform * glm::vec3(uv, 1.0f)); }
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

    /** Glass as the plugin sees it: any transmission. */
    bool isTransmissive() const { return hasTransmission && transmissionFactor > 0.0f; }
};

} // namespace scene
