// Glass selection and per-material optics.
#include "Optics.h"

#include <cmath>
#include <limits>

namespace refraction {

Optics opticsFor(const plugin::ParameterSet& p, const scene::Material* m) {
    Optics o;
    const double iorOverride = p.number("ior");
    const double ior = iorOverride >= 1.0
                           ? iorOverride
                           : (m && m->hasIor && m->ior >= 1.0f ? double(m->ior) : 1.5);
    const double dispersion =
        p.number("dispersion") >= 0.0 ? p.number("dispersion") : (m ? double(m->dispersion) : 0.0);
    // KHR_materials_dispersion: the indices spread around ior by the Abbe number (20 / dispersion).
    const double halfSpread = (ior - 1.0) * 0.025 * dispersion;
    o.ior = glm::vec3(float(ior - halfSpread), float(ior), float(ior + halfSpread));
    o.dispersion = halfSpread > 0.0;
    const auto tint = p.color("tint");
    const glm::vec3 attenuation = (m ? m->attenuationColor : glm::vec3(1.0f)) *
                                  glm::vec3(float(tint[0]), float(tint[1]), float(tint[2]));
    const double distanceOverride = p.number("absorption-distance");
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
    }
    return o;
}

bool isGlass(const plugin::ParameterSet& p, const scene::Model& model,
             const scene::Primitive& primitive) {
    if (p.choice("method") == "opaque")
        return false;
    if (p.choice("glass") == "all")
        return true;
    return primitive.material >= 0 &&
           model.materials[std::size_t(primitive.material)].isTransmissive();
}

} // namespace refraction
