// Private to the plugin: which primitives are glass and their optical constants, shared by the
// GPU passes and the reference tracer so both read the same settings.
#pragma once

#include "engine/plugin/ParameterSet.h"
#include "engine/scene/Model.h"

#include <glm/glm.hpp>

namespace refraction {

/** Per-primitive optics from the material and the global overrides. */
struct Optics {
    glm::vec3 ior; ///< per channel (R, G, B): the KHR_materials_dispersion spread
    bool dispersion = false;
    glm::vec3 sigma{0.0f}; ///< Beer-Lambert absorption per world unit
    float transmission = 1.0f;
    glm::vec4 baseColor{1.0f};
    /** The material's for glass materials; 0 for meshes forced to glass (--glass all plays
     *  them as clear glass, not as frosted copies of their opaque materials). */
    float roughness = 0.0f, metallic = 0.0f;
};

Optics opticsFor(const plugin::ParameterSet& parameters, const scene::Material* material);

/** True when `primitive` renders as glass under `parameters` (method, glass auto|all). */
bool isGlass(const plugin::ParameterSet& parameters, const scene::Model& model,
             const scene::Primitive& primitive);

} // namespace refraction
