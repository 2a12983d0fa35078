// The parts figure's hammered-glass head: its texture coordinates and tangents, and the normal
// map itself.
#include "HammeredHead.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace generate {

using glm::dvec3;

namespace {
const dvec3 kHeadCentre(0.0, 1.655, 0.01); // the head ellipsoid's centre (Figure.cpp)
}

/** Spherical texture coordinates around the head's centre (the seam at the back). */
std::vector<float> headUv(const std::vector<dvec3>& positions) {
    std::vector<float> uv;
    for (const dvec3& p : positions) {
        const dvec3 d = glm::normalize(p - kHeadCentre);
        uv.push_back(float(0.5 + std::atan2(d.x, d.z) / (2.0 * M_PI)));
        uv.push_back(float(std::acos(std::clamp(d.y, -1.0, 1.0)) / M_PI));
    }
    return uv;
}

/** Tangents of headUv()'s mapping: along increasing u (around the head's vertical axis) in each
 *  vertex's tangent plane, the handedness from the direction of increasing v (downwards). */
std::vector<float> headTangents(const std::vector<dvec3>& positions,
                                const std::vector<dvec3>& normals) {
    std::vector<float> tangents;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const dvec3 d = positions[i] - kHeadCentre;
        const double phi = std::atan2(d.x, d.z);
        const dvec3 around(std::cos(phi), 0.0, -std::sin(phi));
        const dvec3& n = normals[i];
        dvec3 t = around - n * glm::dot(n, around);
        t = glm::length(t) > 1e-9 ? glm::normalize(t) : glm::normalize(glm::cross(dvec3(0, 1, 0), n) + dvec3(1e-9, 0, 0));
        const double w = glm::dot(glm::cross(n, t), dvec3(0.0, -1.0, 0.0)) < 0.0 ? -1.0 : 1.0;
        tangents.insert(tangents.end(), {float(t.x), float(t.y), float(t.z), float(w)});
    }
    return tangents;
}

/** A hammered-glass normal map: round dimples on a jittered grid, tileable, 128 x 128. */
capture::Image hammeredNormals() {
    constexpr int kSize = 128, kCells = 8;
    auto height = [](double x, double y) {
        double h = 0.0;
        for (int cy = -1; cy <= kCells; ++cy)
            for (int cx = -1; cx <= kCells; ++cx) {
                const int wx = (cx + kCells) % kCells, wy = (cy + kCells) % kCells;
                const double jx = 0.5 + 0.3 * std::sin(double(wx * 7 + wy * 13)),
                             jy = 0.5 + 0.3 * std::cos(double(wx * 11 + wy * 5));
                const double dx = x * kCells - (cx + jx), dy = y * kCells - (cy + jy);
                const double r2 = dx * dx + dy * dy;
                if (r2 < 0.36)
                    h -= (0.36 - r2) * (0.36 - r2);
            }
        return h;
    };
    capture::Image image{kSize, kSize, std::vector<std::uint8_t>(kSize * kSize * 4)};
    const double e = 1.0 / kSize;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const double u = (x + 0.5) / kSize, v = (y + 0.5) / kSize;
            const double gx = (height(u + e, v) - height(u - e, v)) / (2 * e);
            const double gy = (height(u, v + e) - height(u, v - e)) / (2 * e);
            const dvec3 n = glm::normalize(dvec3(-gx * 0.6, -gy * 0.6, 1.0));
            std::uint8_t* texel = &image.rgba[std::size_t(y * kSize + x) * 4];
            for (int c = 0; c < 3; ++c)
                texel[c] = std::uint8_t(std::lround((n[c] * 0.5 + 0.5) * 255.0));
            texel[3] = 255;
        }
    return image;
}

} // namespace generate
