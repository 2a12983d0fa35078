// The refraction passes of one frame, recorded into the frame graph (ARCHITECTURE.md, "One
// frame"): d_N, the surfaces (one gathered geometry pass or the papers' two), the depth range,
// and the shading (deferred over the glass pixels, or per front fragment plus a composite).
// Private to the plugin.
#pragma once

#include "GpuState.h"
#include "Settings.h"

#include "engine/fg/Blackboard.h"
#include "engine/fg/FrameGraph.h"
#include "engine/plugin/ParameterSet.h"
#include "engine/plugin/Plugin.h"
#include "engine/render/FrameInfo.h"

#include <functional>
#include <vector>

namespace refraction {

/** A frame's decisions and what its passes share, copied into every pass's callback (the
 *  callbacks run after addPasses() returns). */
struct FrameContext {
    GpuState* gpu = nullptr;
    const plugin::Plugin* plugin = nullptr; ///< owner of the glass items (DrawItem::owner)
    Settings settings;                      ///< the parameters, decoded once this frame
    const render::FrameInfo* frame = nullptr;
    bool reflect = false; ///< TIR reflect (two interfaces): the front surface is searched too
    bool onePass = false; ///< the single gathered geometry pass
    /** The first glass item and its index in the frame's items: with one pass, its material
     *  and overrides are every one's. */
    const render::DrawItem* glass = nullptr;
    std::size_t glassIndex = 0;
    const gl::Program* layerShade = nullptr; ///< the shading variant (layerShadeProgram)

    bool isGlass(const render::DrawItem& item) const { return item.owner == plugin; }
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
};

/** Forgets the d_N of characters no longer in `items` (removed, or placed again). */
void dropStaleDistances(GpuState& gpu, std::span<const render::DrawItem> items);

/** The frame graph's buffers the passes order themselves by: the engine's deformed vertices
 *  and the plugin's own (GpuState: d_N, the glass rectangle, the depth range, the layers),
 *  imported each
 *  frame. A pass that writes one leaves the new version here for the passes after it. */
struct FrameBuffers {
    fg::BufferHandle vertices, distances, rectangle, range;
    fg::BufferHandle materials; ///< GpuState::glassMaterials (glass_materials.glsl)
    fg::BufferHandle layers;    ///< GpuState::layers (the layered path)
};

/** The maps the searches read. */
struct SurfaceMaps {
    fg::TextureHandle backDepth, backNormal;   ///< DIR §3.1 (one pass: the gathered near target)
    fg::TextureHandle frontDepth, frontNormal; ///< TIR reflection only
    fg::TextureHandle gatheredFar, mask;       ///< one pass: d_N keys; the glass pixels
};

/** The frame's buffers: the engine's vertices from the blackboard, the plugin's imported. */
FrameBuffers importBuffers(fg::FrameGraph& graph, const fg::Blackboard& blackboard, GpuState& gpu);
/** ISR: d_N of every deformed vertex, cast on the cage every frame. */
void addNormalDistancePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers);
/** The papers' geometry passes: back faces (farthest or `firstBack`), and front faces for TIR
 *  reflection. */
SurfaceMaps addSeparateSurfacePasses(fg::FrameGraph& graph, const FrameContext& c,
                                     const FrameBuffers& buffers, bool firstBack);
/** One geometry pass (MAX blending) over the glass rectangle, then the resolve pass. */
SurfaceMaps addGatheredSurfacePasses(fg::FrameGraph& graph, const fg::Blackboard& blackboard,
                                     const FrameContext& c, FrameBuffers& buffers);
/** The depth range of the back (and front) maps, into GpuState::range. */
void addDepthRangePass(fg::FrameGraph& graph, const FrameContext& c, const SurfaceMaps& maps,
                       FrameBuffers& buffers);
/** The layered path's programs for this frame: the capture for capacity K and the shading
 *  variant for K, the method and the dispersion search (compiled in: layers.glsl,
 *  layers_shade.frag.glsl), built when first needed (every method's at once) and kept. */
core::Result<const gl::Program*> layerShadeProgram(GpuState& gpu, const FrameContext& c);
/** The frame's glass ids and their optics (GpuState::glassIds, glassOptics); ids past the 255
 *  a layer can name share the last, with a warning. */
void assignGlassIds(FrameContext& c);
/** The optics of every glass id into GpuState::glassMaterials, which every shading pass reads. */
void addGlassMaterialsPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers);
/** The layered path: the capture pass (one geometry pass, every glass layer) and the walk over
 *  the glass pixels; returns the new scene colour. */
fg::TextureHandle addLayerPasses(fg::FrameGraph& graph, const fg::Blackboard& blackboard,
                                 const FrameContext& c, FrameBuffers& buffers);
/** Bytes per pixel the layered path keeps at capacity K: the per-pixel head, K layers, the
 *  depth maps the walk reads and, with `outlines`, the outline pass's map. */
std::size_t layerBytesPerPixel(int capacity, bool outlines);

/** The shading, composited over the scene colour: returns the new scene colour. */
fg::TextureHandle addShadingPasses(fg::FrameGraph& graph, const fg::Blackboard& blackboard,
                                   const FrameContext& c, const SurfaceMaps& maps,
                                   const FrameBuffers& buffers);

} // namespace refraction
