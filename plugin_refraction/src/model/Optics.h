// Private to the plugin: the optical constants of a glass primitive, shared by the GPU passes
// and the reference tracer so both read the same settings.
#pragma once

#include "Settings.h"

#include "engine/scene/Model.h"
#include "engine/scene/World.h"

#include <glm/glm.hpp>

namespace refraction {

/** Per-primitive optics: a character's own overrides (scene files: ior, tint, dispersion)
 *  first, then the plugin's parameters (ior, dispersion, tint, absorption distance) where set,
 *  then the material. The factors: the textures multiply them where a path meets the surface
 *  (GlassModel.h's GlassSurface). */
struct Optics {
    glm::vec3 ior; ///< per channel (R, G, B): the KHR_materials_dispersion spread
    bool dispersion = false;
    glm::vec3 sigma{0.0f}; ///< Beer-Lambert absorption per world unit
    float transmission = 1.0f;
    glm::vec4 baseColor{1.0f};
    /** The material's for glass materials; 0 for meshes forced to glass (--glass all plays
     *  them as clear glass, not as frosted copies of their opaque materials). */
    float roughness = 0.0f, metallic = 0.0f;
    // The glass material's surface layers (none for meshes forced to glass): its
    // KHR_materials_specular colour and weight, its clear coat, sheen and iridescent film (the
    // factors: glass reads no textures but its normal map)
    glm::vec3 specularColor{1.0f};
    float specularWeight = 1.0f;
    float clearcoat = 0.0f, clearcoatRoughness = 0.0f;
    glm::vec3 sheenColor{0.0f};
    float sheenRoughness = 0.0f;
    float iridescence = 0.0f, iridescenceIor = 1.3f, iridescenceThickness = 0.0f;
};

/** `extent`: the glass's size in world units (glassExtent), the distance over which a tint acts
 *  on glass whose material sets none (KHR_materials_volume's attenuation distance). */
Optics opticsFor(const Settings& settings, const scene::Material* material,
                 const scene::GlassOverrides& overrides = {}, double extent = 1.0);

/** The sides of a model's box at rest (render's animatedBounds, the rest pose). */
glm::vec3 restSides(const scene::Model& model);
/** A character's glass size: the smallest side of its model's box at rest (`sides`, restSides)
 *  that a ray can cross, scaled by the character's scale. */
double glassExtent(glm::vec3 sides, const scene::Character& character);

} // namespace refraction
