// The reference's photon map: a hash grid of cells one radius wide, a gather visiting the 27
// cells around the point.
#include "PhotonMap.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace refraction {

namespace {

/** A cell's key: its three coordinates, 21 bits each (wrapping: cells that share a key are
 *  told apart by the distance test). */
std::uint64_t packCell(const glm::i64vec3& cell) {
    constexpr std::uint64_t mask = (1u << 21) - 1u;
    return (std::uint64_t(cell.x) & mask) | (std::uint64_t(cell.y) & mask) << 21 |
           (std::uint64_t(cell.z) & mask) << 42;
}

} // namespace

PhotonMap::PhotonMap(std::vector<Photon> photons, double radius)
    : mPhotons(std::move(photons)), mRadius(radius) {
    std::sort(mPhotons.begin(), mPhotons.end(), [this](const Photon& a, const Photon& b) {
        return cellKey(a.point) < cellKey(b.point);
    });
    for (std::size_t i = 0; i < mPhotons.size();) {
        const std::uint64_t key = cellKey(mPhotons[i].point);
        std::size_t end = i;
        while (end < mPhotons.size() && cellKey(mPhotons[end].point) == key)
            ++end;
        mCells.emplace(key, std::pair{std::uint32_t(i), std::uint32_t(end)});
        i = end;
    }
}

std::uint64_t PhotonMap::cellKey(const glm::dvec3& P) const {
    return packCell(glm::i64vec3(glm::floor(P / mRadius)));
}

glm::dvec3 PhotonMap::irradiance(const glm::dvec3& P) const {
    glm::dvec3 sum(0.0);
    const glm::i64vec3 centre(glm::floor(P / mRadius));
    const double r2 = mRadius * mRadius;
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                const auto it = mCells.find(packCell(centre + glm::i64vec3(x, y, z)));
                if (it == mCells.end())
                    continue;
                for (std::uint32_t i = it->second.first; i < it->second.second; ++i) {
                    const glm::dvec3 d = mPhotons[i].point - P;
                    if (glm::dot(d, d) <= r2)
                        sum += mPhotons[i].light;
                }
            }
    return sum / (std::numbers::pi * r2);
}

} // namespace refraction
