// The reference's caustics (docs/materials.md, "Caustics"): the photons one light sent through
// the glass, where they landed on a receiver and the light each carries, in a hash grid of
// cells as wide as the gather radius, for a density estimate around any point.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace refraction {

struct Photon {
    glm::dvec3 point; ///< where it landed (world)
    glm::dvec3 light; ///< what it carries, per channel: the light's intensity as 1
};

class PhotonMap {
public:
    PhotonMap() = default;
    /** The photons, gathered within `radius` of a point. */
    PhotonMap(std::vector<Photon> photons, double radius);

    /** The photons' light within the radius of P over the disc's area: the irradiance they
     *  bring, per channel (a flat receiver's; the radius is the estimate's bias, the photons
     *  in it its noise). */
    glm::dvec3 irradiance(const glm::dvec3& P) const;
    std::size_t size() const { return mPhotons.size(); }

private:
    std::uint64_t cellKey(const glm::dvec3& P) const;
    std::vector<Photon> mPhotons; ///< sorted by cell
    std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> mCells;
    double mRadius = 1.0;
};

} // namespace refraction
