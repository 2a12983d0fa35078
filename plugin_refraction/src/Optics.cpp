// Per-material optics under the settings' overrides.
#include "Optics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refraction {

Optics opticsFor(const Settings& s, const scene::Material* m,
                 const scene::GlassOverrides& overrides) {
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
    const glm::vec3 attenuation = (m ? m->attenuationColor : glm::vec3(1.0f)) *
                                  (overrides.tint ? *overrides.tint : glm::vec3(s.tint));
    const double distanceOverride = s.absorptionDistance;
    const float distance = distanceOverride > 0.0 ? float(distanceOverride)
                           : m                    ? m->attenuationDistance
                                                  : std::numeric_limits<float>::infinity();
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

} // namespace refraction
