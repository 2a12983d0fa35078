// Surface nets over an implicit field (the generated figure's body and eyes): a vertex per grid
// cell the surface crosses, a quad per crossed grid edge, the vertices pulled onto the surface.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace generate {

/** A triangle mesh with a normal a vertex. */
struct Surface {
    std::vector<glm::dvec3> positions, normals;
    std::vector<std::uint32_t> indices;
};

/** The gradient of `f` at `p`, by central differences. */
glm::dvec3 gradient(const std::function<double(const glm::dvec3&)>& f, const glm::dvec3& p);

/** The surface f = 0 (inside where f < 0) over the box [lo, hi], sampled every `h`: its
 *  vertices on the surface, normals from the gradient, triangles wound counter-clockwise from
 *  outside. */
Surface surfaceNets(const std::function<double(const glm::dvec3&)>& f, glm::dvec3 lo, glm::dvec3 hi,
                    double h);

} // namespace generate
