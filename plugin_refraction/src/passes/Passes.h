// The refraction plugin's passes, one file each in this folder, recorded into the frame graph by
// RefractionPlugin::addPasses (ARCHITECTURE.md, "One frame"). Both paths start alike: d_N for
// ISR (NormalDistancePass) and the frame's glass optics (GlassMaterialsPass). Then
//   the layers (default): LayerCapturePass (every glass surface of every character, one
//     geometry pass) -> LayerDepthsPass (the depths as maps) -> LayerShadePass (the walk over
//     the glass pixels) -> LayerOutlinePass (optional: anti-aliased outlines);
//   the papers' two surfaces: SurfacePass (the papers' geometry passes, back faces and for TIR
//     the front) or GatherPass + ResolvePass (one gathered geometry pass), DepthRangePass,
//     then ShadePass (deferred over the glass pixels, after the gathered pass) or
//     FrontFacesPass + CompositePass.
// Each pass's function declares what it reads and writes; the buffers the passes order
// themselves by (FrameBuffers) carry the version the last writer left. Private to the plugin.
#pragma once

#include "../GpuState.h"
#include "../Settings.h"

#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"
#include "engine/plugin/Plugin.h"
#include "engine/render/FrameInfo.h"
#include "engine/render/MaterialTextures.h"

#include <cstdint>
#include <functional>

namespace refraction {

// Storage bindings, as the shaders declare them.
constexpr std::uint32_t kVerticesBinding = 0;  ///< common/vertex.glsl: a draw item's vertices
constexpr std::uint32_t kUvsBinding = 1;       ///< glass.vert.glsl: its texture coordinates
constexpr std::uint32_t kDistancesBinding = 2; ///< glass.vert.glsl: its d_N values
constexpr std::uint32_t kRangeBinding = 3;     ///< surfaces.glsl: the depth range
constexpr std::uint32_t kRectangleBinding = 4; ///< glass_rectangle.glsl
constexpr std::uint32_t kLayerHeadsBinding = 5, kLayerDepthsBinding = 6,
                        kLayerAttrsBinding = 7;     ///< layers.glsl
constexpr std::uint32_t kGlassMaterialsBinding = 8; ///< glass_materials.glsl

// The mip level the two-surface searches read the surface normals at (DIR §3.1: mip-filtered
// normals); the normal maps need no level above it.
constexpr int kNormalLod = 1;

// Texture units: 0-1 the environment; then the pass's maps; the material's slots from
// kMaterialUnit; the gathered far target after them.
constexpr std::uint32_t kMaterialUnit = 8;
constexpr std::uint32_t kGatherFarUnit = kMaterialUnit + render::MaterialTextures::kSlotCount;
constexpr int kSceneColorUnit = 2, kSceneDepthUnit = 3, kLayerDepthUnit = 4, kSurfaceUnit = 6;

/** A frame's decisions and what its passes share, copied into every pass's callback (the
 *  callbacks run after addPasses() returns). */
struct FrameContext {
    GpuState* gpu = nullptr;
    const plugin::Plugin* plugin = nullptr; ///< owner of the glass items (DrawItem::owner)
    Settings settings;                      ///< the parameters, decoded once this frame
    const render::FrameInfo* frame = nullptr;
    bool reflect = false; ///< TIR reflect (two interfaces): the front surface is searched too
    bool onePass = false; ///< the two-surface path's single gathered geometry pass
    /** The first glass item and its index in the frame's items: with one pass, its material
     *  and overrides are every one's. */
    const render::DrawItem* glass = nullptr;
    std::size_t glassIndex = 0;
    const gl::Program* layerShade = nullptr; ///< the shading variant (layerShadeProgram)

    bool isGlass(const render::DrawItem& item) const { return item.owner == plugin; }
    /** Whether the frame has punctual lights (the shading variants with them compiled in). */
    bool lit() const { return !frame->lights.empty(); }
    /** Draws every glass item with `program` (glass.vert.glsl), calling `perItem` (its index
     *  in the frame's items) first when given. */
    void
    drawGlass(const gl::Program& program, const gl::PipelineState& state,
              const std::function<void(const render::DrawItem&, std::size_t)>& perItem = {}) const;
    /** The glass's pixel rectangle and view-space box from the deformed cages
     *  (rectangle.comp.glsl), into GpuState::rectangle. */
    void growGlassRectangle() const;
    /** Draws the glass rectangle (rectangle.vert.glsl) with the bound program against the bound
     *  mask: the early depth test runs the program only on glass pixels. */
    void drawMaskedRectangle() const;
    /** The glass rectangle with the state as it is (no mask test unless set). */
    void drawRectangle() const;
    /** What every shading pass sets alike: method, search, TIR policy, Fresnel, debug view,
     *  camera, the lookup's parameters and the environment (texture units 0-1). */
    void setWalkUniforms(const gl::Program& program) const;
    /** The glass id of frame item `index` (its optics in glass_materials.glsl) and its
     *  material's textures, for `program`. */
    void setMaterial(const gl::Program& program, std::size_t index) const;
    /** layers.glsl's uniforms and the layer arrays. */
    void setLayerUniforms(const gl::Program& program) const;
};

/** The frame graph's buffers the passes order themselves by: the engine's deformed vertices
 *  and the plugin's own (GpuState: d_N, the glass rectangle, the depth range, the layers, the
 *  optics), imported each frame. A pass that writes one leaves the new version here for the
 *  passes after it. */
struct FrameBuffers {
    fg::BufferHandle vertices, distances, rectangle, range;
    fg::BufferHandle materials; ///< GpuState::glassMaterials (glass_materials.glsl)
    fg::BufferHandle layers;    ///< GpuState::layers (the layered path)
};

/** The scene the glass is drawn over, from the blackboard. */
struct SceneInputs {
    fg::TextureHandle color, depth;
};

/** The two-surface path's maps the searches read. */
struct SurfaceMaps {
    fg::TextureHandle backDepth, backNormal;   ///< DIR §3.1 (one pass: the gathered near target)
    fg::TextureHandle frontDepth, frontNormal; ///< TIR reflection only
    fg::TextureHandle gatheredFar, mask;       ///< one pass: d_N keys; the glass pixels
};

// ---- Shared by the passes (FrameContext.cpp)

/** The frame's buffers: the engine's vertices from the blackboard, the plugin's imported. */
FrameBuffers importBuffers(fg::FrameGraph& graph, const fg::Blackboard& blackboard, GpuState& gpu);
SceneInputs sceneInputs(const fg::Blackboard& blackboard);
/** Forgets the d_N of characters no longer in `items` (removed, or placed again). */
void dropStaleDistances(GpuState& gpu, std::span<const render::DrawItem> items);
/** The frame's glass ids and their optics (GpuState::glassIds, glassOptics); ids past the 255
 *  a layer can name share the last, with a warning. */
void assignGlassIds(FrameContext& c);
/** The layered path's programs for this frame: the capture for capacity K and the shading
 *  variant for K, the method and the dispersion search (compiled in: layers.glsl,
 *  layers_shade.frag.glsl), built when first needed (every method's at once) and kept. */
core::Result<const gl::Program*> layerShadeProgram(GpuState& gpu, const FrameContext& c);
/** Bytes per pixel the layered path keeps at capacity K: the per-pixel head, K layers, the
 *  depth maps the walk reads and, with `outlines`, the outline pass's map. */
std::size_t layerBytesPerPixel(int capacity, bool outlines);
/** Depth slots per pixel: whole vec4s (layers.glsl reads four at once). */
std::size_t layerDepthSlots(int capacity);

gl::TextureDesc colorDesc(glm::ivec2 size);
gl::TextureDesc depthDesc(glm::ivec2 size);
gl::TextureDesc normalDesc(glm::ivec2 size);
gl::TextureDesc zDesc(glm::ivec2 size);

// ---- Both paths

/** ISR: d_N of every deformed vertex, cast on the cage every frame (writes distances). */
void addNormalDistancePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers);
/** The optics of every glass id into GpuState::glassMaterials, which every shading pass reads. */
void addGlassMaterialsPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers);

// ---- The layers

/** Every glass surface into the layer arrays (writes layers, rectangle); returns the glass
 *  pixels' mask. */
fg::TextureHandle addLayerCapturePass(fg::FrameGraph& graph, const FrameContext& c,
                                      FrameBuffers& buffers);
/** The layers' depths as the maps the walk's searches read (one or two RGBA32F). */
struct LayerDepths {
    fg::TextureHandle depths0, depths1;
};
LayerDepths addLayerDepthsPass(fg::FrameGraph& graph, const FrameContext& c,
                               const FrameBuffers& buffers, fg::TextureHandle mask);
/** The walk over the glass pixels: the new scene colour and, for the outline pass, each
 *  pixel's nearest layer (writes rectangle: the overflow count). */
struct LayerShade {
    fg::TextureHandle color, surface;
};
LayerShade addLayerShadePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                             const SceneInputs& scene, fg::TextureHandle mask,
                             const LayerDepths& depths);
/** The outlines of smooth glass anti-aliased; returns the new scene colour. */
fg::TextureHandle addLayerOutlinePass(fg::FrameGraph& graph, const FrameContext& c,
                                      const FrameBuffers& buffers, const LayerShade& shaded);

// ---- The papers' two surfaces

/** The papers' geometry passes: back faces (farthest or `firstBack`), and front faces for TIR
 *  reflection. */
SurfaceMaps addSurfacePasses(fg::FrameGraph& graph, const FrameContext& c,
                             const FrameBuffers& buffers, bool firstBack);
/** One geometry pass, MAX blending, over the glass (writes rectangle). */
struct Gathered {
    fg::TextureHandle nearTargets, farTargets;
};
Gathered addGatherPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers);
/** The gathered targets resolved into the maps and the glass mask. */
SurfaceMaps addResolvePass(fg::FrameGraph& graph, const FrameContext& c,
                           const FrameBuffers& buffers, const SceneInputs& scene,
                           const Gathered& gathered);
/** The depth range of the back (and front) maps, into GpuState::range (writes range,
 *  rectangle). */
void addDepthRangePass(fg::FrameGraph& graph, const FrameContext& c, const SurfaceMaps& maps,
                       FrameBuffers& buffers);
/** The glass shaded over the glass pixels after the gathered pass; returns the new scene
 *  colour. */
fg::TextureHandle addShadePass(fg::FrameGraph& graph, const FrameContext& c,
                               const SurfaceMaps& maps, const FrameBuffers& buffers,
                               const SceneInputs& scene);
/** The front faces refracted and shaded, depth-tested; returns the glass image. */
fg::TextureHandle addFrontFacesPass(fg::FrameGraph& graph, const FrameContext& c,
                                    const SurfaceMaps& maps, const FrameBuffers& buffers,
                                    const SceneInputs& scene);
/** The glass image over the scene colour; returns the new scene colour. */
fg::TextureHandle addCompositePass(fg::FrameGraph& graph, const FrameContext& c,
                                   const SceneInputs& scene, fg::TextureHandle glass);

/** What ShadePass and FrontFacesPass read alike, and the uniforms and maps of
 *  glass_shading.glsl they set alike. */
struct TwoSurfaceShadeData {
    SurfaceMaps maps;
    fg::TextureHandle sceneColor, sceneDepth, out, zbuffer;
};
void readTwoSurfaceInputs(fg::Builder& b, const FrameContext& c, const SurfaceMaps& maps,
                          const FrameBuffers& buffers, const SceneInputs& scene,
                          TwoSurfaceShadeData& d);
void setTwoSurfaceShading(const FrameContext& c, const gl::Program& program,
                          const TwoSurfaceShadeData& d, const fg::Resources& r);

} // namespace refraction
