// The scene renderer: a world of characters through deform -> background -> opaque ->
// (lighting, opaque_layers) -> (ground) -> plugin stages -> tonemap, recorded into a frame graph
// every frame (one file per pass: src/render/passes/), executed, timed per pass on CPU and GPU.
#pragma once

#include "engine/anim/Pose.h"
#include "engine/core/Result.h"
#include "engine/deform/GpuDeformer.h"
#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"
#include "engine/fg/Pool.h"
#include "engine/gl/Commands.h"
#include "engine/gl/Context.h"
#include "engine/gl/Framebuffer.h"
#include "engine/gl/Program.h"
#include "engine/gl/ProgramCache.h"
#include "engine/plugin/Plugin.h"
#include "engine/render/Environment.h"
#include "engine/render/FrameInfo.h"
#include "engine/render/MaterialTextures.h"
#include "engine/scene/World.h"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace render {

struct RenderGpu;
struct CharacterGpu;
struct ShadowAtlases;

/** One executed pass: CPU time of its execute callback and its GPU time: with
 *  RenderSettings::exactPassTimes this frame's, the wall clock from an idle GPU to the pass's
 *  work finished; else a timer query's, the newest earlier frame's that the GPU has finished
 *  (up to 3 frames old; reading it never waits). */
struct PassStats {
    std::string name;
    double cpuMs = 0.0;
    double gpuMs = 0.0;
};

struct FrameStats {
    std::vector<PassStats> passes;
    double cpuMs = 0.0; ///< whole frame on the CPU (animate, record, compile, execute)
    /** CPU time to pose every character, upload all their skin matrices and morph weights
     *  (one buffer update each), and build and claim the draw items (part of cpuMs). */
    double animateMs = 0.0;
    /** CPU time to record the frame graph (the engine's passes and the plugins') and compile
     *  it (part of cpuMs). With animateMs, the engine's own CPU work per frame: the rest of
     *  cpuMs is issuing GL commands, which on a CPU rasteriser includes running them. */
    double recordMs = 0.0;
    double gpuMs = 0.0;             ///< sum of the passes' GPU times
    std::size_t transientBytes = 0; ///< GPU memory of the frame graph's pooled textures, buffers
    std::size_t historyBytes = 0;   ///< GPU memory of the temporal history (0 while off)
    std::string graph;              ///< the compiled frame graph as text
};

class Renderer {
public:
    /** Programs and the environment (prefiltered); no world yet. Needs a current context. */
    static core::Result<std::unique_ptr<Renderer>> create(const asset::HdrImage& environment,
                                                          gl::Context& context);
    ~Renderer();

    /** Adds a plugin (not owned): initialises it now, then it adds passes every frame. */
    core::Status addPlugin(plugin::Plugin* plugin);

    /** Brings the GPU state up to `world`: each model is uploaded once (GpuModel, material
     *  textures), whatever number of characters place it; each character gets a placement of
     *  it (GpuDeformer), kept while the character at that index places the same model. Models
     *  no character places any more are released. render() calls it; a tool calls it first to
     *  reach geometry() before a frame. The renderer shares the models (no lifetime rule). On
     *  failure (a limit, a topology OpenSubdiv rejects) the error names the character. */
    core::Status prepare(const scene::World& world);

    /** Renders `world` at scene time `time` seen by `camera` into output() (RGBA8,
     *  sRGB-encoded, size settings.size): each character posed by what it plays at `time`
     *  (anim::evaluate) and placed by its transform, every character's skin matrices
     *  and morph weights uploaded at once, deformed, then the frame graph. With
     *  settings.temporal on, the frame is jittered and blended into the history kept across
     *  calls (TemporalHistory). Fails (no crash) on a
     *  preparation or frame graph error, naming the character or the pass. */
    core::Result<FrameStats> render(const scene::World& world, const Camera& camera,
                                    const RenderSettings& settings, double time = 0.0);

    const gl::Texture& output() const { return mOutput; }
    /** The output's pixels, rows top to bottom, RGBA8 (synchronises). */
    std::vector<std::uint8_t> readOutput() const;
    /** The output of an hdrOutput frame as RGBA floats, rows top to bottom (synchronises). */
    std::vector<float> readHdrOutput() const;

    /** Shows the last output() in the window: rectangle `source` (x, y, width, height, GL's
     *  bottom-up rows) of it to rectangle `destination` of the default framebuffer (scaled
     *  bilinearly when the sizes differ). */
    void presentOutput(glm::ivec4 source, glm::ivec4 destination) const;

    /** The motion texels (common/motion.glsl) the last frame that accumulated resolved with:
     *  RGBA32UI, GL's bottom-up rows; empty while off (tests and debug tools). */
    const gl::Texture& lastMotion() const;

    /** Starts the temporal history over on the next frame: a camera cut the caller knows of (the
     *  renderer finds the others itself: TemporalHistory::begin). */
    void resetHistory();

    /** Replaces the environment (prefiltered again); on failure the previous one stays. */
    core::Status setEnvironment(const asset::HdrImage& environment);

    /** Rebuilds every model's deformed geometry with OpenSubdiv refinement to `level` (0: the
     *  file's meshes as they are; up to core::limits::kMaxSubdivisionLevel); models added later
     *  are refined alike. On failure (a topology OpenSubdiv rejects, a limit) the current
     *  geometry stays and the error names the mesh. */
    core::Status setSubdivisionLevel(int level);
    int subdivisionLevel() const { return mLevel; }

    /** Sets where the ground plane is drawn when settings.ground is on. */
    void setGround(const GroundPlane& ground) { mGroundPlane = ground; }
    const GroundPlane& ground() const { return mGroundPlane; }
    const Environment& environment() const;

    gl::ShaderLibrary& shaders() { return mShaders; }
    /** How many program variants the renderer and its plugins have compiled so far (its
     *  ProgramCache): a frame like one drawn before compiles none. */
    std::size_t programVariants() const { return mPrograms->size(); }
    /** Their keys (gl::ProgramCache::keys): each variant's shaders and defines. */
    std::vector<std::string> programVariantKeys() const { return mPrograms->keys(); }
    /** Characters of the world last prepared, and each one's deformed geometry (as the last
     *  frame left it). */
    std::size_t characterCount() const;
    const deform::GpuDeformer& geometry(std::size_t character) const;
    /** The draw items of the last frame (every character's primitives, with their owners). */
    std::span<const DrawItem> drawItems() const;

private:
    Renderer() = default;
    /** This frame's shadow views (RenderGpu::shadows) of its lights around the characters. */
    void planShadows(const scene::World& world, const RenderSettings& settings);
    // The frame's steps (render), in order.
    /** Poses every character at `time`, stages its skin and morph uploads, places its lights
     *  and lists its draw items (RenderGpu::poses, lights, items); whether the opaque pass
     *  draws anything besides the background (the ground, or an item no plugin claims). */
    bool animate(const scene::World& world, const RenderSettings& settings, double time);
    /** Character `c`'s draw items, each claimed by the first plugin that wants it, into
     *  RenderGpu::items; whether one is left to the opaque pass. */
    bool listItems(std::size_t c, const scene::Character& character, CharacterGpu& cg);
    /** The frame's lights (the characters' and the scene file's, none without
     *  RenderSettings::lights), their shadow views, uploaded for every pass. */
    core::Status light(const scene::World& world, const RenderSettings& settings);
    /** What the passes read of this frame (its place in the temporal history too). */
    FrameInfo describeFrame(const scene::World& world, const Camera& camera,
                            const RenderSettings& settings, double time, bool opaqueGeometry);
    /** The engine's passes and the plugins' at their stages, into `graph`, through
     *  `blackboard`; the frame's lighting features from what the plugins drew into the shadow
     *  atlases. */
    core::Status record(fg::FrameGraph& graph, FrameInfo& frame, fg::Blackboard& blackboard);
    /** The lights' shadow atlases (the engine's empty ones where none casts), on the
     *  blackboard for the plugins to draw into; returns them as the engine left them. */
    ShadowAtlases recordShadows(fg::FrameGraph& graph, fg::Blackboard& blackboard,
                                const FrameInfo& frame, fg::BufferHandle vertices);
    /** Runs the compiled graph, each pass timed (RenderSettings::exactPassTimes), into
     *  `stats`; ends the temporal history's frame and the pool's. */
    core::Status execute(fg::FrameGraph& graph, const FrameInfo& frame, FrameStats& stats);
    class TextureAllocator;
    class BufferAllocator;
    class Timer;
    gl::Context* mContext = nullptr;
    int mLevel = 0;
    gl::ShaderLibrary mShaders;
    std::unique_ptr<gl::ProgramCache> mPrograms; ///< every pass's variants, over mShaders
    std::unique_ptr<TextureAllocator> mTextureAllocator;
    std::unique_ptr<fg::TexturePool> mTextures; ///< the frame graph's transient textures
    std::unique_ptr<BufferAllocator> mBufferAllocator;
    std::unique_ptr<fg::BufferPool> mBuffers; ///< and buffers
    // What the passes draw with; declared after the pool so that its framebuffer goes before
    // the pooled textures it may still hold.
    std::unique_ptr<RenderGpu> mGpu;
    std::unique_ptr<Timer> mTimer;
    std::vector<plugin::Plugin*> mPlugins;
    gl::Texture mOutput;
    mutable gl::Framebuffer mPresent;
    GroundPlane mGroundPlane;
};

} // namespace render
