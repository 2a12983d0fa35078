// The refraction plugin's passes, one file each in this folder, named like the pass and its
// shader (a pass drawn twice takes a suffix: pair_surface.back, .front), recorded into the frame
// graph by RefractionPlugin::addPasses (ARCHITECTURE.md, "One frame"): one pipeline, a capture and
// the walk, all at the AfterOpaque stage:
//   glass_materials (GlassMaterialsPass): the frame's glass optics;
//   glass_bvh (GlassBvhPass; ISR, the tracing methods and the caustics): the BVH refitted,
//     ISR's d_N cast;
//   where lights cast: glass_shadow (GlassShadowPass): the glass into the engine's glass atlas,
//     the caustics' emitters marked; with caustics, caustic_photons -> caustic_resolve. The
//     engine's shading reads the atlases as the frame leaves them, so these run before it;
//   glass_extent (GlassExtentPass): where the glass lies on screen and in view space;
// then the capture, either
//   the layers (default): layer_capture (LayerCapturePass: every glass surface of every
//     character, K a pixel, one geometry pass) -> layer_overflow (LayerOverflowPass: the
//     overflowing pixels' kept layers bid for their fallback) -> layer_depths (LayerDepthsPass:
//     their depths as maps, for the methods that search them: not SIR), or
//   the pair (the papers' two-surface model): pair_gather (PairGatherPass: one MAX-blended
//     geometry pass) or pair_surface.back and .front (PairSurfacePass: the papers' two
//     depth-tested ones) -> pair_resolve (PairResolvePass: the pair as layers 0 and 1, with the
//     maps the papers' search reads);
// then walk (WalkPass: the walk over the glass pixels), for the hybrid hybrid_trace
// (HybridTracePass: the pixels its walk handed over, traced), where the history will reject
// glass pixels fresh_samples (FreshSamplesPass: more samples there) and, optionally, outlines
// (OutlinesPass: the outlines anti-aliased). Each pass's function declares what it reads and
// writes; the buffers the passes order themselves by (FrameBuffers) carry the version the last
// writer left. What the passes share is in FrameContext.cpp (descriptors, imports, uniforms,
// draws), Variants.cpp (the defines the passes' programs are keyed by), GlassIds.cpp (the glass ids
// and their optics) and LayerStorage.cpp (the layer arrays' sizes). Private to the plugin.
#pragma once

#include "../GpuState.h"
#include "../Settings.h"
#include "../Shared.h"

#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"
#include "engine/plugin/Plugin.h"
#include "engine/render/FrameInfo.h"
#include "engine/render/MaterialTextures.h"
#include "engine/render/ShadowAtlases.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace refraction {

// Bindings and units: the registry's (Shared.h, refraction::slot; the engine's gl::slot).

// The mip level the papers' search over the pair reads the surface normals at (DIR §3.1:
// mip-filtered normals); the normal maps need no level above it.
constexpr int kNormalLod = 1;

/** Where the glass is drawn from: the camera's view and projection, or a light's. */
struct GlassView {
    glm::mat4 view, projection;
};

/** The layer arrays (layers.glsl), lent by the frame graph for one frame: transient buffers
 *  the capture (or the pair's resolve) creates for `shape`, which every pass after it reads or
 *  writes through these handles. surfaces: with textured glass only; motions: a word where the
 *  frame does not accumulate (layers.glsl declares them). */
struct LayerBuffers {
    LayerShape shape;
    fg::BufferHandle heads, depths, attrs, surfaces, motions;
};

/** What a pass that draws the glass draws it with, as the frame graph lends it: the glass
 *  materials (glass_materials.glsl) and, for ISR, the BVH whose d_N the glass's vertices read
 *  (readGlassDrawn, which also declares the read of the deformed vertices). */
struct GlassDrawn {
    fg::BufferHandle materials, bvh;
};

/** A frame's decisions and what its passes share, copied into every pass's callback (the
 *  callbacks run after addPasses() returns). */
struct FrameContext {
    GpuState* gpu = nullptr;
    const plugin::Plugin* plugin = nullptr; ///< owner of the glass items (DrawItem::owner)
    Settings settings;                      ///< the parameters, decoded once this frame
    const render::FrameInfo* frame = nullptr;
    bool reflect = false; ///< TIR reflect (two interfaces): the pair's front is searched too
    bool onePass = false; ///< the pair drawn in one MAX-blended geometry pass
    /** The first glass item's glass id: with the pair in one pass, every one's. */
    int firstGlassId = 0;
    /** Some glass of the frame has textures the walk reads (its base colour, transmission or
     *  roughness): the capture keeps each layer's surface (GLASS_TEXTURES). Which of them:
     *  some a base colour texture (GLASS_BASE_COLOR_TEXTURES); some, authored transmissive, a
     *  transmission or metallic-roughness texture (GLASS_TRANSMISSION_TEXTURES). A texture read
     *  that no glass of the frame needs is out of the programs that read them. */
    bool texturedGlass = false;
    bool baseColorTexturedGlass = false, transmissionTexturedGlass = false;
    /** Some glass of the frame has a normal map (GLASS_NORMAL_MAPS of the captures and the
     *  glass shadow, which read it per fragment). */
    bool normalMappedGlass = false;
    /** What of the glass's model the frame's glass uses, as the defines of every program that
     *  shades or crosses it (glassDefines): surface layers, KHR_materials_specular, the film,
     *  partial transmission, textures, normal maps. */
    std::vector<std::string> glassModel;
    /** The lights cast this frame and the glass casts its shadow (Settings::glassShadows). */
    bool shadowed = false;
    /** With it, the glass focuses their caustics (Settings's focusesCaustics): the BVH holds
     *  the opaque parts, which the photons may meet. */
    bool caustics = false;

    bool isGlass(const render::DrawItem& item) const { return item.owner == plugin; }
    /** The variant of the program of `vertex` and `fragment` (or of the compute shader `name`)
     *  under `defines`, from the engine's program cache, which compiles it the first time any
     *  frame asks for it: each pass asks for its own where it executes. One that does not
     *  compile is an error naming its file ("refraction: ..."), which stops the frame there. */
    core::Result<const gl::Program*> graphics(const std::string& vertex,
                                              const std::string& fragment,
                                              const std::vector<std::string>& defines = {}) const;
    core::Result<const gl::Program*> compute(const std::string& name,
                                             const std::vector<std::string>& defines = {}) const;
    /** The BVH holds the opaque parts too, which a traced ray or a photon may meet. */
    bool bvhHoldsOpaque() const { return settings.traces() || caustics; }
    /** The walk reads the layers' depths from maps (refraction.layer_depths, or the pair's
     *  resolve): every method that looks past a pixel's own layers. SIR's walk reads only its
     *  pixel's, from the arrays, and its frame has no layer_depths pass (WALK_DEPTH_MAPS). */
    bool layerDepthMaps() const {
        return !settings.layered() || settings.method != Settings::Method::Sir;
    }
    /** The camera's view and projection. */
    GlassView cameraView() const { return {frame->camera.view, frame->camera.projection}; }
    /** Draws every glass item with `program` (glass.vert.glsl) from `from` (the camera's when
     *  not given), calling `perItem` (its index in the frame's items) first when given; d_N
     *  from `glass`'s BVH where it was read. */
    void drawGlass(const gl::Program& program, const gl::PipelineState& state,
                   const fg::Resources& r, const GlassDrawn& glass,
                   const std::function<void(const render::DrawItem&, std::size_t)>& perItem = {},
                   const std::optional<GlassView>& from = {}) const;
    /** Draws the glass rectangle (rectangle.vert.glsl: from the glass's extent `extent`) with
     *  the bound program against the bound mask: the early depth test runs the program only on
     *  glass pixels. */
    void drawMaskedRectangle(const gl::Buffer& extent, gl::Blend blend = gl::Blend::None) const;
    /** The glass rectangle with the state as it is (no mask test unless set). */
    void drawRectangle(const gl::Buffer& extent) const;
    /** What the walk and the outline pass set alike: searches and march, TIR policy, Fresnel,
     *  debug view, camera, the lookup's parameters and the environment (texture units 0-1). */
    void setWalkUniforms(const gl::Program& program) const;
    /** Draws every glass item with `program`, its glass id and material textures set, and
     *  `glass`'s materials bound, from `from` (the camera's when not given). */
    void drawGlassMaterials(const gl::Program& program, const gl::PipelineState& state,
                            const fg::Resources& r, const GlassDrawn& glass,
                            const std::optional<GlassView>& from = {}) const;
    /** layers.glsl's uniforms and the layer arrays `layers`. */
    void setLayerUniforms(const gl::Program& program, const fg::Resources& r,
                          const LayerBuffers& layers) const;
    /** The trace's and the hybrid's samples a frame (one where the frame accumulates). */
    int traceSamples() const;
    /** Where the frame accumulates while anything moves (its history's second frame on), the
     *  samples a glass pixel takes where its history will be rejected (Settings::freshSamples:
     *  the first jittered with the frame, the others over the pixel: traced for the trace and
     *  the hybrid, walked for DIR), every other pixel one; 1 in any other frame, a debug view
     *  or a method that takes none (Settings::freshSampled). */
    int freshSamples() const;
    /** The frame takes samples past a pixel's first: traceSamples() or freshSamples() over 1
     *  for a method that traces (SEVERAL_SAMPLES). */
    bool severalSamples() const;
    /** The walk's rays meet the nearby opaque scene (the nearby lookup on, opaque geometry
     *  drawn: NEARBY_SCENE), and the ground square where it is drawn (NEARBY_GROUND). */
    bool seesNearbyScene() const;
    /** The walk marches through the nearby opaque scene (it sees it, with a method that does
     *  not trace): the scene's depth tiles help it. */
    bool marchesScene() const;
    /** The scene's depth tiles (R32F): a texel a tile of 4 x 4 pixels, and levels of tiles up to
     *  128 pixels as the frame allows. */
    gl::TextureDesc sceneTiles() const;
};

/** The frame graph's buffers the passes order themselves by: the engine's deformed vertices,
 *  the plugin's storage kept across frames (GpuState), imported each frame, and the transient
 *  buffers this frame's passes create once they have. A pass that writes one leaves the new
 *  version here for the passes after it. */
struct FrameBuffers {
    fg::BufferHandle vertices;   ///< the engine's deformed vertices (plugin::kSceneVertices)
    fg::BufferHandle bvh;        ///< GpuState::glass: the glass BVH and ISR's d_N
    fg::BufferHandle extent;     ///< the glass's extent (glass_extent.glsl; transient)
    fg::BufferHandle pairRanges; ///< the pair's (pair_ranges.glsl), from its resolve (transient)
    fg::BufferHandle counters;   ///< GpuState::counters (walk_counters.glsl)
    fg::BufferHandle materials;  ///< GpuState::glassMaterials (glass_materials.glsl)
    LayerBuffers layers;         ///< what the capture holds (transient)
    fg::BufferHandle handedOver; ///< the hybrid's list (walk.glsl), from the walk (transient)
    /** The caustics' storage (caustics.glsl; transient, from the glass shadow pass): the
     *  emitters (a count, the photons' work groups, a bit a texel, the photon list) and the sums
     *  (four words a cell, the fine cells' then the coarse). */
    fg::BufferHandle causticEmitters, causticSums;
};

/** The scene the glass is drawn over, from the blackboard; where the frame accumulates, the
 *  motion of its pixels. */
struct SceneInputs {
    fg::TextureHandle color, depth, motion;
    /** With motion: the history's colour and the previous frame's motion (plugin::kHistory*). */
    fg::TextureHandle historyColor, historyMotion;
    /** The shadow atlases: what the lights' shading reads. */
    render::ShadowAtlases shadows;
    /** Where the walk marches through the scene: its nearest depth over tiles (the scene's
     *  depth tiles pass, added after the rest). */
    fg::TextureHandle depthTiles;
};

/** What a capture leaves the walk: the glass pixels' mask and the depth maps (layers.glsl);
 *  the pair's mip-filtered front and back normals for the papers' search. */
struct Capture {
    fg::TextureHandle mask, depths0, depths1;
    fg::TextureHandle normals[2];
};

/** What the walk and the hybrid's trace read alike: the capture, the scene under the glass. */
struct WalkInputs {
    Capture capture;
    LayerBuffers layers;
    fg::BufferHandle extent;
    fg::BufferHandle pairRanges; ///< with the pair
    fg::BufferHandle materials;
    fg::BufferHandle bvh; ///< where the method traces
    fg::TextureHandle sceneColor, sceneDepth, sceneDepthTiles;
    render::ShadowAtlases shadows;
};
/** Declares what the walk reads as read by the pass: the capture's maps, the scene's colour
 *  and depth, the shadow atlases, the extent, layers, materials, the pair's ranges and, where
 *  the method traces, the BVH. */
WalkInputs readWalkInputs(fg::Builder& b, const FrameContext& c, const FrameBuffers& buffers,
                          const SceneInputs& scene, const Capture& capture);
/** Binds them, with the glass BVH and its textures where the method traces, and the walk's
 *  counters `counters` (which the pass writes). */
core::Status bindWalkInputs(const fg::Resources& r, const FrameContext& c, const WalkInputs& in,
                            fg::BufferHandle counters);
/** The history's colour and motion (SceneInputs' historyColor, historyMotion) at the engine's
 *  history units, for the fresh samples' choice (walk_motion.glsl). */
void bindHistory(const fg::Resources& r, fg::TextureHandle color, fg::TextureHandle motion);
/** The frame's glass textures at the traced textures' units (traced_surface.glsl), for the
 *  trace's and the photons' hits. */
void bindTracedTextures(const GpuState& gpu);

// ---- Shared by the passes (FrameContext.cpp)

/** The frame's buffers: the engine's vertices from the blackboard, the plugin's imported. */
FrameBuffers importBuffers(fg::FrameGraph& graph, const fg::Blackboard& blackboard, GpuState& gpu);
/** The glass BVH the graph lends as `bvh` (FrameBuffers::bvh, imported as an object). */
GpuState::Glass& glassBvh(const fg::Resources& r, fg::BufferHandle bvh);
/** Declares the reads of what the glass is drawn with (GlassDrawn): the vertices, the
 *  materials and, for ISR, the BVH's d_N. */
GlassDrawn readGlassDrawn(fg::Builder& b, const FrameContext& c, const FrameBuffers& buffers);
SceneInputs sceneInputs(const fg::Blackboard& blackboard);
gl::TextureDesc colorDesc(glm::ivec2 size);
/** The walk's colour target: single precision where it adds samples up (in half floats each
 *  sum rounds: 64 samples came out darker by up to 0.7/255), else colorDesc's. */
gl::TextureDesc walkDesc(glm::ivec2 size, const Settings& settings);
gl::TextureDesc normalDesc(glm::ivec2 size);
gl::TextureDesc zDesc(glm::ivec2 size);

// ---- The glass ids and their optics (GlassIds.cpp)

/** The frame's glass ids and their optics (GpuState::glassIds, glassOptics); ids past the 255
 *  a layer can name share the last, with a warning. */
void assignGlassIds(FrameContext& c);

// ---- The programs' defines (Variants.cpp): what each pass's variant is keyed by

/** "NAME value", a define. */
std::string define(const std::string& name, int value);
/** `a`, then `b`. */
std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b);

/** What of the glass's model the frame's glass uses (FrameContext::glassModel). */
std::vector<std::string> glassDefines(const FrameContext& c);
/** The layers' capture, overflow bids and depth maps: the glass model, K, the textures' level
 *  and motion. */
std::vector<std::string> layerDefines(const FrameContext& c);
/** The walk's variant for `method`: the capture (the pair, or the layers' K), the dispersion
 *  search, the frame's lighting features (FrameInfo::lighting), what of the glass's model it
 *  uses, motion, the debug view, several samples a pixel, what of the nearby scene its rays
 *  can meet. */
std::vector<std::string> walkDefines(const FrameContext& c, Settings::Method method);

// ---- The layer arrays (LayerStorage.cpp)

/** The layer arrays for `shape` (surfaceSlots: 0, none, or with textured glass K, and then the
 *  overflow fallback bids for its surfaces in the heads), created and written by the pass `b`
 *  declares (their contents undefined until it writes them). */
LayerBuffers createLayers(fg::Builder& b, const LayerShape& shape);
/** Declares that the pass writes (on top of) every array of `layers`; returns the new versions. */
LayerBuffers writeLayers(fg::Builder& b, const LayerBuffers& layers);
/** Declares that the pass reads every array of `layers`; returns the versions read. */
LayerBuffers readLayers(fg::Builder& b, const LayerBuffers& layers);
/** Bytes per pixel the layered path keeps at capacity K: the per-pixel head, K layers,
 *  `surfaceSlots` surfaces, the depth maps the walk reads and, with `outlines`, the outline
 *  pass's map. */
std::size_t layerBytesPerPixel(int capacity, bool outlines, int surfaceSlots = 0);
/** Planes of a word a pixel in the layer heads: the count and the fallback's bids (layers.glsl's
 *  LayerHeads). The list of the overflowing pixels follows them: its header of
 *  kOverflowListHeader words (the count, the work groups), then a word a pixel. */
std::size_t layerHeadPlanes(int surfaceSlots);
inline constexpr std::size_t kOverflowListHeader = 4;
/** Where the list of the overflowing pixels starts in the layer heads, in bytes. */
std::size_t overflowListOffset(const LayerShape& shape);
/** Words per pixel in the layer heads, the overflow list's included. */
std::size_t layerHeadWords(int surfaceSlots);
/** Depth slots per pixel: whole vec4s (layers.glsl reads four at once). */
std::size_t layerDepthSlots(int capacity);

// ---- Before the capture

/** The optics of every glass id into GpuState::glassMaterials, which the walk reads. */
void addGlassMaterialsPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers);
/** `refraction.glass_shadow` (GlassShadowPass.cpp): the glass from every shadow view into the
 *  engine's glass atlas `atlas`, and with the caustics their emitters marked; returns the
 *  atlas's new version. */
fg::TextureHandle addGlassShadowPass(fg::FrameGraph& graph, const FrameContext& c,
                                     FrameBuffers& buffers, fg::TextureHandle atlas);
/** `refraction.caustic_photons` (CausticPhotonsPass.cpp): photons from the emitters the glass
 *  shadow pass marked, refracted through the glass BVH onto the receivers whose depth the
 *  shadow depth atlas `depth` holds, summed (writes caustics). */
void addCausticPhotonsPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                           fg::TextureHandle depth);
/** `refraction.caustic_resolve` (CausticResolvePass.cpp): the photons' sums filtered into a new
 *  caustics atlas over the shadow views' tiles; returns it (plugin::kShadowCaustics). */
fg::TextureHandle addCausticResolvePass(fg::FrameGraph& graph, const FrameContext& c,
                                        FrameBuffers& buffers);
/** The caustics atlas's size: the shadow atlases' over kCausticScale. */
inline glm::ivec2 causticSize(const FrameContext& c) {
    return c.frame->shadows->atlasSize / kCausticScale;
}
/** What the photons' passes and the resolve share: the atlas's size and the budget. */
inline void setCausticUniforms(const gl::Program& program, const FrameContext& c) {
    program.set("uCausticSize", causticSize(c));
    program.set("uPhotonBudget", c.settings.causticPhotons);
}
/** ISR and trace: the glass BVH refitted (or rebuilt) to the frame's deformed glass; for ISR
 *  d_N of every deformed vertex cast against it (writes bvh). */
void addGlassBvhPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers);
/** The glass's pixel rectangle and view-space box from the deformed cages (writes extent). */
void addGlassExtentPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers);

// ---- The capture: the layers

/** Every glass surface into the layer arrays (writes layers); returns the glass pixels'
 *  mask. */
fg::TextureHandle addLayerCapturePass(fg::FrameGraph& graph, const FrameContext& c,
                                      FrameBuffers& buffers);
/** `refraction.layer_overflow` (LayerOverflowPass.cpp): the kept layers of the pixels the
 *  capture listed as overflowing bid for their fallback (writes layers). */
void addLayerOverflowPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers);
/** The layers' depths as the maps the walk's searches read (one or two RGBA32F). */
Capture addLayerDepthsPass(fg::FrameGraph& graph, const FrameContext& c,
                           const FrameBuffers& buffers, fg::TextureHandle mask);

// ---- The capture: the pair

/** The pair as the geometry passes leave it: the MAX-blended targets of one pass, or the
 *  front and back maps (depth and d_N; normal and glass id) of the papers' two. */
struct PairTargets {
    fg::TextureHandle nearTargets, farTargets;
    fg::TextureHandle frontDepth, frontNormal, backDepth, backNormal;
    fg::TextureHandle frontSurface, backSurface; ///< the two passes' with textured glass
};
/** One geometry pass, MAX blending, over the glass. */
PairTargets addPairGatherPass(fg::FrameGraph& graph, const FrameContext& c,
                              const FrameBuffers& buffers);
/** The papers' two geometry passes: back faces (farthest, or `firstBack`) and front faces. */
PairTargets addPairSurfacePasses(fg::FrameGraph& graph, const FrameContext& c,
                                 const FrameBuffers& buffers, bool firstBack);
/** The pair resolved into layers 0 and 1, the depth ranges and the mask (writes layers,
 *  pairRanges). */
Capture addPairResolvePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                           const SceneInputs& scene, const PairTargets& pair);

// ---- The walk

/** The walk over the glass pixels: the new scene colour, for the outline pass each pixel's
 *  nearest layer, and where the frame accumulates, the scene's motion with the glass pixels'
 *  (walk_motion.glsl) (writes counters; handedOver where it lists pixels: the hybrid's handed
 *  over, those that take the fresh samples). */
struct Walked {
    fg::TextureHandle color, surface, motion;
};
/** `refraction.scene_depth_tiles`: the scene's nearest depth over tiles, for the walk's marches
 *  (scene_depth_tiles.comp.glsl); returns the chain. */
fg::TextureHandle addSceneDepthTilesPass(fg::FrameGraph& graph, const FrameContext& c,
                                         fg::TextureHandle sceneDepth);
Walked addWalkPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                   const SceneInputs& scene, const Capture& capture);
/** A listed pass's resources (ListedSamples.cpp): the walk's inputs and outputs, its motion
 *  and history where the frame accumulates. */
struct TraceData {
    WalkInputs in;
    fg::TextureHandle sceneMotion, historyColor, historyMotion, color, motion;
    fg::BufferHandle counters, handedOver;
};
/** The pixels a listed pass samples: those the hybrid's walk handed over, or the fresh ones. */
enum class ListedPixels : int { HandedOver, Fresh };
/** Declares a listed pass's reads and writes over the walk's outputs. */
void declareListedSamples(fg::Builder& b, TraceData& d, const FrameContext& c,
                          FrameBuffers& buffers, const SceneInputs& scene, const Capture& capture,
                          const Walked& walked, ListedPixels list);
/** Samples [first, last) of the list's pixels, each weighing 1 / `samples`. */
core::Status sampleList(const fg::Resources& r, const TraceData& d, const FrameContext& c,
                        ListedPixels list, int first, int last, int samples);
/** `refraction.hybrid_trace` (HybridTracePass.cpp): the hybrid's handed-over pixels traced over
 *  the walk's colour (and motion); returns the new versions (writes counters; the fresh
 *  samples' list). */
Walked addHybridTracePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                          const SceneInputs& scene, const Capture& capture, const Walked& walked);
/** `refraction.fresh_samples` (FreshSamplesPass.cpp), where c.freshSamples() > 1 (the trace and
 *  the hybrid): the later samples of the listed
 *  pixels (those whose history will be rejected, or differs from their first sample) traced
 *  and added to the walk's colour; returns its new version. */
Walked addFreshSamplesPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                           const SceneInputs& scene, const Capture& capture, const Walked& walked);
/** The outlines of smooth glass anti-aliased over the walk's colour, into the scene colour
 *  (the walk read it: no copy); returns its new version. */
fg::TextureHandle addOutlinesPass(fg::FrameGraph& graph, const FrameContext& c,
                                  const FrameBuffers& buffers, const SceneInputs& scene,
                                  const Walked& walked);

} // namespace refraction
