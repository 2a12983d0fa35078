// The default environment: a sunset sky, a coloured skyline along the horizon, a tiled floor.
#include "Sky.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace generate {
namespace {

constexpr double kPi = 3.141592653589793;

/** A well-mixed 32-bit hash of an integer, mapped to [0, 1). */
double hash01(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return double(x) / 4294967296.0;
}

const glm::dvec3 kZenith{0.10, 0.22, 0.62};
const glm::dvec3 kHorizon{1.25, 0.86, 0.62};

glm::dvec3 sky(const glm::dvec3& d) {
    const double t = std::pow(1.0 - std::max(d.y, 0.0), 3.0);
    glm::dvec3 c = glm::mix(kZenith, kHorizon, t);
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.55, 0.2, -0.8));
    const double s = std::max(glm::dot(d, sun), 0.0);
    c += glm::dvec3(60.0, 48.0, 34.0) * std::pow(s, 3000.0) +
         glm::dvec3(0.9, 0.45, 0.15) * std::pow(s, 12.0);
    return c;
}

/** Buildings along the horizon: 64 slices of azimuth, each a block of its own height and
 *  colour with lit windows, or a gap. Returns false where the sky shows. */
bool skyline(double azimuth, double elevation, glm::dvec3& colour) {
    static const glm::dvec3 kPalette[] = {{0.05, 0.75, 0.70}, {0.85, 0.12, 0.55},
                                          {1.00, 0.62, 0.10}, {0.45, 0.85, 0.15},
                                          {0.85, 0.10, 0.10}, {0.12, 0.30, 0.95}};
    const double slices = 64.0;
    const double x = (azimuth / (2.0 * kPi) + 0.5) * slices;
    const auto slice = std::uint32_t(std::floor(x));
    const double within = x - std::floor(x);
    if (hash01(slice * 3u + 1u) < 0.18 || within < 0.06 || within > 0.94)
        return false;                                             // a gap between blocks
    const double height = 0.035 + 0.17 * hash01(slice * 3u + 2u); // radians above the horizon
    if (elevation < 0.0 || elevation > height)
        return false;
    const glm::dvec3 base =
        kPalette[std::size_t(hash01(slice * 3u + 3u) * 6.0) % 6] * (0.55 + 0.6 * hash01(slice));
    // Windows: a grid of brighter cells on the facade.
    const double columns = within * 8.0, rows = elevation / 0.012;
    const bool window =
        std::fmod(columns, 1.0) > 0.35 && std::fmod(rows, 1.0) > 0.45 &&
        hash01(slice * 131u + std::uint32_t(columns) * 17u + std::uint32_t(rows) * 7919u) > 0.4;
    colour = window ? glm::dvec3(2.4, 2.1, 1.5) : base;
    return true;
}

glm::dvec3 floor(const glm::dvec3& d) {
    // A plane 1.6 m below the viewer, tiled every metre, fading into haze at the horizon.
    const double distance = 1.6 / std::max(-d.y, 1e-4);
    const glm::dvec3 p = d * distance;
    const bool dark = (int(std::floor(p.x)) + int(std::floor(p.z))) & 1;
    const glm::dvec3 tile = dark ? glm::dvec3(0.16, 0.14, 0.13) : glm::dvec3(0.52, 0.46, 0.40);
    return glm::mix(kHorizon * 0.6, tile, std::exp(-distance * 0.03));
}

} // namespace

asset::HdrImage buildSky(int width) {
    asset::HdrImage image{width, width / 2, {}};
    image.rgb.resize(std::size_t(image.width) * std::size_t(image.height) * 3u);
    constexpr int kSamples = 3; // per axis, against aliasing of the tiles and windows
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            glm::dvec3 sum(0.0);
            for (int sy = 0; sy < kSamples; ++sy)
                for (int sx = 0; sx < kSamples; ++sx) {
                    // The engine's equirectangular mapping (render::Environment): u = 0.5
                    // looks down -z, v = 0 straight up.
                    const double u = (x + (sx + 0.5) / kSamples) / image.width;
                    const double v = (y + (sy + 0.5) / kSamples) / image.height;
                    const double phi = (u - 0.5) * 2.0 * kPi, theta = v * kPi;
                    const glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                                       -std::sin(theta) * std::cos(phi));
                    glm::dvec3 c;
                    if (skyline(phi, kPi / 2.0 - theta, c))
                        sum += c;
                    else
                        sum += d.y >= 0.0 ? sky(d) : floor(d);
                }
            const glm::dvec3 c = sum / double(kSamples * kSamples);
            for (int k = 0; k < 3; ++k)
                image.rgb[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3u +
                          std::size_t(k)] = float(c[k]);
        }
    return image;
}

} // namespace generate
