// The frame's lighting beyond the environment: the punctual lights placed in the world, and the
// sheen layer's albedo table, in the storage buffer common/lighting.glsl reads (bound for the
// whole frame at gl::slot::kLighting).
#pragma once

#include "engine/core/Limits.h"
#include "engine/gl/Buffer.h"
#include "engine/render/Shadows.h"
#include "engine/scene/Light.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace anim {
struct Pose;
}
namespace scene {
struct Model;
struct World;
} // namespace scene

namespace render {

constexpr int kSheenTableSize = 16;

/** E(NoV, roughness), the directional albedo of KHR_materials_sheen's lobe (Charlie
 *  distribution, Ashikhmin visibility) integrated numerically once: row r holds roughness
 *  r / (size - 1), column c NoV c / (size - 1). */
const std::array<float, kSheenTableSize * kSheenTableSize>& sheenAlbedoTable();
/** The table read bilinearly, as common/lighting.glsl reads it on the GPU. */
double sheenAlbedo(double NoV, double roughness);

/** The nodes of `model`'s default scene that carry a light (KHR_lights_punctual). */
std::vector<int> lightNodes(const scene::Model& model);
/** The lights on `nodes` (lightNodes) in `pose`, placed by `placement`, appended to `out`. */
void placeLights(const scene::Model& model, std::span<const int> nodes, const anim::Pose& pose,
                 const glm::dmat4& placement, std::vector<scene::PlacedLight>& out);
/** Every light of `world` at scene time `time`: its characters' (posed) and its own. */
std::vector<scene::PlacedLight> worldLights(const scene::World& world, double time);

/** The shadow views the lighting buffer holds at most: every shadowed light a point light's six. */
constexpr std::size_t kMaxShadowViews = 6 * core::limits::kMaxShadowedLights;

/** The lighting buffer on the GPU: the sheen table, the light and shadow view counts, the
 *  shadow views (common/shadows.glsl), then the lights, each naming its first view. */
class LightingBuffer {
public:
    /** Writes `lights` and their `shadows` (growing the buffer when they do not fit) and binds
     *  it. */
    void upload(const std::vector<scene::PlacedLight>& lights, const ShadowPlan& shadows);

private:
    gl::Buffer mBuffer;
    std::size_t mCapacity = 0;
    std::vector<std::uint8_t> mStaging; ///< the count and the packed lights (storage reused)
};

} // namespace render
