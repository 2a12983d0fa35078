// What a frame knows, shared with plugins through the blackboard under plugin::kFrame.
#pragma once

#include "engine/render/Camera.h"

#include <glm/glm.hpp>

namespace scene {
struct Model;
}
namespace deform {
class GpuDeformer;
}
namespace gl {
class ShaderLibrary;
}

namespace render {

class Environment;
class MaterialTextures;

/** The ground plane drawn when RenderSettings::ground is on: a square at `height`, centred
 *  under `center`, 2 * halfSize wide, world units. */
struct GroundPlane {
    float height = 0.0f;
    glm::vec3 center{0.0f};
    float halfSize = 1.0f;
};

/** Display and scene settings of a frame. */
struct RenderSettings {
    glm::ivec2 size{256, 256};
    float exposure = 1.0f;
    float environmentRotation = 0.0f; ///< radians about +y
    float environmentIntensity = 1.0f;
    float backgroundBlur = 0.0f; ///< roughness of the background lookup
    bool ground = false;
    /** Finish the GPU work of each pass before timing its end. Tile-deferred rasterisers
     *  (llvmpipe) otherwise bill a pass's rasterisation to whichever pass flushes it; this
     *  gives true per-pass times at the cost of pipelining. */
    bool exactPassTimes = false;
    /** Output the HDR scene colour unchanged (RGBA32F, no exposure, tonemap or sRGB) instead of
     *  the display image: for measurements and debug views. */
    bool hdrOutput = false;
};

struct FrameInfo {
    const scene::Model* model = nullptr;
    const deform::GpuDeformer* geometry = nullptr; ///< this frame's deformed vertex buffers
    const Environment* environment = nullptr;
    const MaterialTextures* materials = nullptr;
    const gl::ShaderLibrary* shaders = nullptr;
    Camera camera;
    RenderSettings settings;
    double time = 0.0;
    GroundPlane ground; ///< drawn when settings.ground
    /** Whether the opaque pass draws anything besides the background: the ground, or a
     *  primitive no plugin claims. Screen-space effects that look for nearby geometry can skip
     *  their search when it is false (the background alone is the environment). */
    bool opaqueGeometry = false;
};

} // namespace render
