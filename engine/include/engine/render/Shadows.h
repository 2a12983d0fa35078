// The frame's shadow maps: which lights cast, each light's views (a spot's perspective, a
// directional light's box fitted to the casters, a point light's six cube faces) and their
// tiles in one depth atlas, which the `shadows` pass draws and every shading pass samples
// through common/shadows.glsl (docs/materials.md, "Shadows").
#pragma once

#include "engine/core/Result.h"
#include "engine/render/Camera.h"
#include "engine/scene/Light.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <span>
#include <vector>

namespace render {

/** What the glass atlas holds where no glass lies along a light's ray: its nearest distance
 *  past everything (a half float's largest). */
constexpr float kNoGlass = 65504.0f;

/** One map of one light: its view of the casters and its square tile in the atlas. */
struct ShadowView {
    std::size_t light = 0; ///< index into the frame's lights
    glm::mat4 view{1.0f};  ///< world -> the light's view (rigid: distances kept)
    glm::mat4 projection{1.0f};
    bool perspective = true; ///< spot and point lights; directional ones are orthographic
    glm::ivec3 tile{0};      ///< x, y and side of the tile in the atlas, texels
    /** World size of one texel: at distance 1 from the light (perspective), or anywhere. */
    float texelSize = 0.0f;
    /** The near plane's distance: where the glass atlas's distances along the light's rays
     *  start (small numbers, which its half floats keep). */
    float near = 0.0f;
    glm::mat4 viewProjection() const { return projection * view; }
};

/** What casts this frame: every view, the atlas they share, per light its first view. */
struct ShadowPlan {
    std::vector<ShadowView> views;
    glm::ivec2 atlasSize{0};
    std::vector<int> firstView; ///< per light of the frame: its first view, -1 for none
    /** Lights that asked for shadows over core::limits::kMaxShadowedLights: lit unshadowed. */
    std::size_t overLimit = 0;
    /** The resolutions were halved this many times for the atlas to fit the GPU's textures. */
    int halved = 0;
    bool empty() const { return views.empty(); }
};

/** Which of `lights` cast shadows: those whose LightShadow is enabled and that shine, the first
 *  core::limits::kMaxShadowedLights of them (the GPU's shadow views and the reference alike). */
std::vector<bool> castingLights(std::span<const scene::PlacedLight> lights);

/** The views of every light in `lights` that casts (LightShadow::enabled, up to the limit)
 *  around `casters`, the world bounds of everything that casts, packed into an atlas at most
 *  `maxTextureSize` texels a side. */
ShadowPlan planShadows(std::span<const scene::PlacedLight> lights, const Bounds& casters,
                       int maxTextureSize);

} // namespace render
