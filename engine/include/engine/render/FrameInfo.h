// What a frame knows, shared with plugins through the blackboard under plugin::kFrame.
#pragma once

#include "engine/render/Camera.h"
#include "engine/render/LightingFeatures.h"
#include "engine/render/Shadows.h"
#include "engine/scene/Light.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace scene {
struct Model;
struct Primitive;
struct Character;
struct World;
} // namespace scene
namespace deform {
class GpuDeformer;
struct GpuPrimitive;
} // namespace deform
namespace gl {
class Program;
class ProgramCache;
class Sampler;
class ShaderLibrary;
class VertexArray;
} // namespace gl
namespace plugin {
class Plugin;
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

    /** The plane the tools put under `bounds`: at their lowest point, centred under them,
     *  three bounding radii wide on each side. */
    static GroundPlane under(const Bounds& bounds) {
        return {bounds.min.y, bounds.center(), 3.0f * std::max(bounds.radius(), 1e-3f)};
    }
};

/** Temporal accumulation: every frame's projection jittered under the pixel, and a resolve
 *  pass that blends the frame into the history the renderer keeps across frames, each pixel
 *  reprojected by its motion (docs/methods.md, "Temporal accumulation"). */
struct TemporalSettings {
    bool enabled = false;
    /** The history's weight while anything moves (the new frame's is 1 - weight, or 1 / n
     *  over the first n frames of a history): higher converges further and lags more, and
     *  the clip then holds more of the history's blur; 0.7 scores best on the playing scenes
     *  measured (docs/accuracy.md). */
    float historyWeight = 0.7f;
    /** The jitter's extent while anything moves, as a share of the pixel (still frames take
     *  the whole pixel): the history is then clipped toward this frame's one sample, and a
     *  sample nearer the pixel's centre is nearer the pixel's mean. Half a pixel scores better
     *  than the whole on every playing scene measured (docs/accuracy.md). */
    float movingJitter = 0.5f;
    /** While nothing moves (a paused viewer, a capture at one time), every frame since the
     *  last change weighs the same: N still frames are N samples of one frame. */
    bool convergeStill = true;
    /** Reject history on disocclusion (depth), a changed surface or path end, and clip it to
     *  the new frame's neighbourhood. Off only to show what they are for. */
    bool rejectHistory = true;
    enum class View {
        Off,      ///< the resolved frame
        Rejected, ///< red where the history was rejected, green where clipped, grey kept
        Motion,   ///< each pixel's motion (hue: direction, brightness: length over 8 px)
    };
    View view = View::Off;
    bool operator==(const TemporalSettings&) const = default;
};

/** Display and scene settings of a frame. */
struct RenderSettings {
    glm::ivec2 size{256, 256};
    float exposure = 1.0f;
    float environmentRotation = 0.0f; ///< radians about +y
    float environmentIntensity = 1.0f;
    float backgroundBlur = 0.0f; ///< roughness of the background lookup
    bool ground = false;
    /** The lights cast shadows (each as its LightShadow says): off, none does. */
    bool shadows = true;
    /** The frame's punctual lights (a file's on its nodes, a scene file's): off, the
     *  environment lights the frame alone (what the lights cost: glass-bench --lights). */
    bool lights = true;
    /** Time each pass alone: the GPU finished before it begins and before it ends, the wall
     *  clock between. A timer query on a tile-deferred rasteriser (llvmpipe) bills a pass's
     *  rasterisation to another pass, even with a finish before its end; this gives true
     *  per-pass times at the cost of pipelining. */
    bool exactPassTimes = false;
    /** Output the HDR scene colour unchanged (RGBA32F, no exposure, tonemap or sRGB) instead of
     *  the display image: for measurements and debug views. */
    bool hdrOutput = false;
    /** A debug view in place of the scene: one of the frame's shadow atlases (where a light
     *  casts), fitted into the frame: the casters' depth, the glass's transmittance, or the
     *  caustics a plugin focused (render/shadow_map_view.frag.glsl). */
    enum class ShadowMapView { Off, Depth, Glass, Caustics };
    ShadowMapView shadowMapView = ShadowMapView::Off;
    TemporalSettings temporal;
    /** For measurement only (glass-bench --skip; docs/performance.md, "Where the time goes"):
     *  each name S compiles every program of the renderer's cache with the define SKIP_S, which
     *  leaves that step of the frame out (the shaders' `#ifdef SKIP_*`). The frames are wrong
     *  by design; empty (the default) changes nothing. */
    std::vector<std::string> skippedSteps;
    bool operator==(const RenderSettings&) const = default;
};

/** This frame's place in the temporal history (FrameInfo::temporal). */
struct TemporalFrame {
    bool enabled = false;
    /** The frame's index in the history since it was last reset (0: the history's first):
     *  the jitter's index in its sequence, and the seed of sampled paths. */
    std::uint32_t index = 0;
    /** Nothing moved since the previous frame: camera, time, placements and world the same. */
    bool still = false;
    /** Pixels (each in -0.5..0.5) FrameInfo::camera is offset by: each pixel's centre sees what
     *  the unjittered frame shows at its centre plus this. */
    glm::vec2 jitter{0.0f};
    /** World -> clip without the jitter, this frame's and the previous frame's (this frame's
     *  on the history's first): what motion vectors measure with. */
    glm::mat4 viewProjection{1.0f}, previousViewProjection{1.0f};
};

/** One primitive of one mesh node of one character, as a frame draws it: the unit plugins
 *  claim. Its deformed vertices are this frame's (read them after the deform pass: declare a
 *  read of "scene.vertices"). */
struct DrawItem {
    std::size_t character = 0;                   ///< index into FrameInfo::world->characters
    const scene::Character* source = nullptr;    ///< glass mode, overrides, name
    const scene::Model* model = nullptr;         ///< the character's model
    const scene::Primitive* primitive = nullptr; ///< the file's primitive (material, skin)
    int material = -1;                           ///< index into model->materials, or -1
    /** The material's factors as the character's pose shows them (KHR_animation_pointer
     *  channels played: anim::materialOf), or null for -1. What passes read, not the model's. */
    const scene::Material* values = nullptr;
    const deform::GpuDeformer* geometry = nullptr;  ///< the character's deformer
    std::uint32_t instance = 0, primitiveIndex = 0; ///< into geometry->instances()
    const deform::GpuPrimitive* gpu = nullptr;      ///< deformed vertices, uvs, index count
    const gl::VertexArray* vertexArray = nullptr;   ///< binds the primitive's index buffer
    const MaterialTextures* materials = nullptr;    ///< the model's textures
    glm::mat4 world{1.0f}; ///< mesh node to world space (the character's placement included)
    /** `world` on the previous frame (GpuInstance::previousMeshToWorld): with the previous
     *  deformation (gpu->previous), what motion vectors measure from. */
    glm::mat4 previousWorld{1.0f};
    /** `world` mirrors (a negative determinant): glTF's winding is reversed, its front faces
     *  clockwise (PipelineState::clockwise; a traced or referenced winding flips too). */
    bool mirrored = false;
    /** Identifies the character's GPU placement across frames (GpuDeformer::serial()): what a
     *  plugin keys per-character caches on. A new value means new vertex buffers. */
    std::uint64_t key = 0;
    /** The plugin that draws this item instead of the opaque pass (the first whose claims()
     *  said yes), or null. */
    const plugin::Plugin* owner = nullptr;
};

struct FrameInfo {
    const scene::World* world = nullptr;
    /** Every primitive of every character, characters in world order, each character's in
     *  its deformer's order (GpuDeformer::instances(), then primitives). */
    std::span<const DrawItem> items;
    const Environment* environment = nullptr;
    /** The frame's punctual lights in world space (a file's on its nodes, a scene file's),
     *  also in the storage buffer at gl::slot::kLighting. */
    std::span<const scene::PlacedLight> lights;
    const gl::ShaderLibrary* shaders = nullptr;
    /** The renderer's program variants, compiled once each (passes ask it for theirs). */
    gl::ProgramCache* programs = nullptr;
    /** The comparing sampler the shadow depth atlas is read through (ShadowAtlases::bind). */
    const gl::Sampler* shadowSampler = nullptr;
    /** The frame's camera: its projection offset by the temporal jitter where accumulating
     *  (temporal.viewProjection is the unjittered one). */
    Camera camera;
    RenderSettings settings;
    TemporalFrame temporal;
    double time = 0.0;  ///< scene time, seconds
    GroundPlane ground; ///< drawn when settings.ground
    /** Whether the opaque pass draws anything besides the background: the ground, or an
     *  item no plugin claims. Screen-space effects that look for nearby geometry can skip
     *  their search when it is false (the background alone is the environment). */
    bool opaqueGeometry = false;
    /** The shadow views of this frame's lights (empty where none casts or
     *  RenderSettings::shadows is off): a plugin that casts draws into their tiles. */
    const ShadowPlan* shadows = nullptr;
    /** What the frame's lights ask of the programs that shade (their defines), known once the
     *  frame is recorded (what the plugins drew into the atlases): a pass picks its variant
     *  where it executes. */
    LightingFeatures lighting;
};

/** Sets common/motion.glsl's uniforms on `program` (this frame's and the previous frame's
 *  unjittered world -> clip, the frame's size) and uWriteMotion: whether the frame accumulates,
 *  so that a pass writes its pixels' motion. */
void setMotionUniforms(const gl::Program& program, const FrameInfo& frame);

} // namespace render
