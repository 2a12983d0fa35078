// The renderer's own passes, one file each, recorded by Renderer::render in this order:
// deform -> background -> ground (optional) -> opaque -> [plugin stages] -> tonemap.
#pragma once

#include "../RenderGpu.h"

#include "engine/fg/FrameGraph.h"
#include "engine/render/FrameInfo.h"

namespace render::passes {

/** The HDR scene colour and depth as the passes hand them on. */
struct SceneTargets {
    fg::TextureHandle color, depth;
};

/** `deform`: deforms each character (GpuDeformer::dispatch) from what they staged into
 *  RenderGpu::poses (uploaded before the frame graph runs); writes `vertices` (the imported
 *  resource standing for every character's deformed buffers), returns the new version. */
fg::BufferHandle addDeform(fg::FrameGraph& graph, RenderGpu& gpu, fg::BufferHandle vertices);
/** `background`: creates scene.color (RGBA16F) and scene.depth (cleared to 1) and draws the
 *  environment behind everything. */
SceneTargets addBackground(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame);
/** `ground`: the ground plane (FrameInfo::ground) into the scene targets. */
SceneTargets addGround(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                       SceneTargets scene);
/** `opaque`: every draw item no plugin claimed, metallic-roughness with image-based lighting,
 *  from the deformed vertices. */
SceneTargets addOpaque(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                       SceneTargets scene, fg::BufferHandle vertices);
/** `tonemap`: exposure, ACES fit and sRGB (or the raw HDR colour) into `output`. */
void addTonemap(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                fg::TextureHandle scene, fg::TextureHandle output);

} // namespace render::passes
