// The project's default character: a glass figure built from a smooth implicit body (capsules
// and ellipsoids blended by a smooth minimum), meshed by surface nets, skinned to a 19-joint
// skeleton, with a breathing morph target and three clips (walk, wave, idle).
#pragma once

#include <cstdint>
#include <vector>

namespace generate {

struct FigureOptions {
    double cellSize = 0.017; ///< metres; the figure is about 1.75 m tall
    /** The body split by part, each its own glass (clear torso, blue arms, amber legs) and a
     *  head of hammered glass (a normal map on spherical texture coordinates). */
    bool parts = false;
};

/** The figure as GLB bytes: one skinned mesh (a glass body with KHR_materials_transmission,
 *  _volume, _ior and _dispersion, or its parts, and opaque eyes), the skeleton, the clips.
 *  Deterministic: the same options give the same bytes. */
std::vector<std::uint8_t> buildFigureGlb(const FigureOptions& options = {});

} // namespace generate
