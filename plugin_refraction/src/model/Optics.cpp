// Per-material optics under the settings' overrides.
#include "Optics.h"

#include "engine/render/Camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refraction {

Optics opticsFor(const Settings& s, const scene::Material* m,
                 const scene::GlassOverrides& overrides, double extent) {
    Optics o;
    const double iorOverride = overrides.ior ? double(*overrides.ior) : s.ior;
    const double ior = iorOverride >= 1.0
                           ? iorOverride
                           : (m && m->hasIor && m->ior >= 1.0f ? double(m->ior) : 1.5);
    const double dispersion = overrides.dispersion  ? double(*overrides.dispersion)
                              : s.dispersion >= 0.0 ? s.dispersion
                              : m                   ? double(m->dispersion)
                                                    : 0.0;
    // KHR_materials_dispersion: the indices spread around ior by the Abbe number (20 / dispersion).
    const double halfSpread = (ior - 1.0) * 0.025 * dispersion;
    o.ior = glm::vec3(float(ior - halfSpread), float(ior), float(ior + halfSpread));
    o.dispersion = halfSpread > 0.0;
    const glm::vec3 tint = overrides.tint ? *overrides.tint : glm::vec3(s.tint);
    const glm::vec3 attenuation = (m ? m->attenuationColor : glm::vec3(1.0f)) * tint;
    // The tint acts on all glass: where the material sets no attenuation distance, over the
    // glass's own extent (the colour white light takes through its thinnest side).
    const float materialDistance =
        m ? m->attenuationDistance : std::numeric_limits<float>::infinity();
    const float distance = s.absorptionDistance > 0.0        ? float(s.absorptionDistance)
                           : std::isfinite(materialDistance) ? materialDistance
                           : tint != glm::vec3(1.0f)         ? float(extent)
                                                             : materialDistance;
    o.sigma = std::isfinite(distance)
                  ? -glm::log(glm::max(attenuation, glm::vec3(1e-4f))) / distance
                  : glm::vec3(0.0f);
    o.transmission = m && m->isTransmissive() ? m->transmissionFactor : 1.0f;
    o.baseColor = m ? m->baseColorFactor : glm::vec4(1.0f);
    if (m && m->isTransmissive()) {
        o.roughness = m->roughnessFactor;
        o.metallic = m->metallicFactor;
        if (m->hasSpecular) {
            o.specularColor = m->specularColorFactor;
            o.specularWeight = m->specularFactor;
        }
        if (m->hasClearcoat) {
            o.clearcoat = m->clearcoatFactor;
            o.clearcoatRoughness = std::max(m->clearcoatRoughnessFactor, 0.03f);
        }
        if (m->hasSheen) {
            o.sheenColor = m->sheenColorFactor;
            o.sheenRoughness = m->sheenRoughnessFactor;
        }
        if (m->hasIridescence) {
            o.iridescence = m->iridescenceFactor;
            o.iridescenceIor = m->iridescenceIor;
            o.iridescenceThickness = m->iridescenceThicknessMaximum;
        }
    }
    return o;
}

glm::vec3 restSides(const scene::Model& model) {
    const render::Bounds rest = render::animatedBounds(model, -1, 1);
    return rest.empty() ? glm::vec3(0.0f) : rest.max - rest.min;
}

double glassExtent(glm::vec3 rest, const scene::Character& character) {
    const glm::vec3 sides = rest * glm::abs(glm::vec3(character.placement.scale));
    // The smallest side a ray can cross (a flat, open sheet's thickness is none).
    const float largest = std::max({sides.x, sides.y, sides.z});
    float smallest = largest;
    for (int axis = 0; axis < 3; ++axis)
        if (sides[axis] > 1e-3f * largest)
            smallest = std::min(smallest, sides[axis]);
    return largest > 0.0f ? double(smallest) : 1.0;
}

} // namespace refraction
