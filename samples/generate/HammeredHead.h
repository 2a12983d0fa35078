// The parts figure's hammered-glass head (Figure.cpp): spherical texture coordinates around
// the head's centre, their tangents, and a tileable normal map of round dimples.
#pragma once

#include "engine/capture/Image.h"

#include <glm/glm.hpp>

#include <vector>

namespace generate {

/** u around the head's vertical axis (the seam at the back), v from the top; two per vertex. */
std::vector<float> headUv(const std::vector<glm::dvec3>& positions);
/** headUv()'s tangents (xyz, handedness w) in each vertex's tangent plane; four per vertex. */
std::vector<float> headTangents(const std::vector<glm::dvec3>& positions,
                                const std::vector<glm::dvec3>& normals);
/** The hammered-glass normal map, 128 x 128, tileable. */
capture::Image hammeredNormals();

} // namespace generate
