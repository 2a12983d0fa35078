// The renderer's own passes, one file each, recorded by Renderer::render in this order:
// deform -> shadows (where lights cast) -> background -> opaque -> lighting and opaque_layers
// (where the frame has punctual lights: OpaquePass.cpp) -> ground (optional: after the
// characters, so that it shades only what they leave) -> [plugin stages] -> temporal (where the
// frame accumulates) -> tonemap. The passes that shade with the lights read the shadow atlases
// as the plugins leave them, so the graph runs the plugins' shadow passes before them. Each asks
// the renderer's program cache (FrameInfo::programs) for its program's variant where it
// executes.
#pragma once

#include "../RenderGpu.h"
#include "../TemporalHistory.h"

#include "engine/fg/FrameGraph.h"
#include "engine/gl/ProgramCache.h"
#include "engine/render/FrameInfo.h"
#include "engine/render/ShadowAtlases.h"

#include <array>
#include <string>
#include <vector>

namespace render::passes {

/** The HDR scene colour and depth as the passes hand them on; where the frame accumulates, the
 *  motion of every pixel (common/motion.glsl, RGBA32UI), each pass writing its own pixels'. */
struct SceneTargets {
    fg::TextureHandle color, depth, motion;
};
/** A pass that shades with the lights: its scene targets and the shadow atlases it reads,
 *  bound where it executes. */
struct LitTargets : SceneTargets {
    ShadowAtlases shadows;
};

/** Whether a pass's program writes motion: the frame accumulates (common/motion.glsl). */
inline std::string motionDefine(const FrameInfo& frame) {
    return std::string("WRITE_MOTION ") + (frame.temporal.enabled ? "1" : "0");
}

/** The surface targets, the deferred shading's G-buffer (common/surface_targets.glsl): world
 *  position and occlusion, shading normal and roughness (RGBA32F), base colour and metallic,
 *  dielectric F0 and specular weight (RGBA16F). */
struct SurfaceTargets {
    fg::TextureHandle position, normal, base, specular;
    /** The four in their order: the writer's colour attachments 1-4, the reader's units. */
    std::array<fg::TextureHandle, 4> all() const { return {position, normal, base, specular}; }
};

/** The defines of a pass that shades with the lights: the frame's lighting features
 *  (FrameInfo::lighting) and whether it writes motion (the frame accumulates). */
inline std::vector<std::string> litDefines(const FrameInfo& frame) {
    std::vector<std::string> defines = frame.lighting.defines();
    defines.push_back(motionDefine(frame));
    return defines;
}

/** The colour target and, where the frame accumulates, the motion target of `scene`. */
inline std::vector<const gl::Texture*> sceneTargets(const fg::Resources& r,
                                                    const SceneTargets& scene) {
    std::vector<const gl::Texture*> targets{&r.texture(scene.color)};
    if (scene.motion.valid())
        targets.push_back(&r.texture(scene.motion));
    return targets;
}

/** `deform`: deforms each character (GpuDeformer::dispatch) from what they staged into
 *  RenderGpu::poses (uploaded before the frame graph runs); writes `vertices` (the imported
 *  resource standing for every character's deformed buffers), returns the new version. */
fg::BufferHandle addDeform(fg::FrameGraph& graph, RenderGpu& gpu, fg::BufferHandle vertices);
/** `shadows`: creates both atlases of FrameInfo::shadows (the depth and the glass; the caustics
 *  left unset), draws every opaque item into each view's tile of the depth atlas and clears the
 *  glass atlas (1 x 1 where no glass casts) for the plugins. */
ShadowAtlases addShadows(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                         fg::BufferHandle vertices);
/** `shadow_map_view`: a new colour target showing the atlas frame.settings.shadowMapView
 *  names (the depth, the glass's or the caustics), fitted into the frame, for the tonemap. */
fg::TextureHandle addShadowMapView(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                                   const ShadowAtlases& shadows);
/** `background`: creates scene.color (RGBA16F) and scene.depth (cleared to 1) and draws the
 *  environment behind everything; where the frame accumulates, creates scene.motion with the
 *  environment's motion. */
SceneTargets addBackground(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame);
/** `ground`: the ground plane (FrameInfo::ground) into the scene targets, shadowed by the
 *  atlases `blackboard` holds once the frame is recorded (ShadowAtlases::readFinal). Drawn after
 *  the characters, it shades only the pixels they leave. */
SceneTargets addGround(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                       SceneTargets scene, const fg::Blackboard& blackboard);
/** The opaque characters: every draw item no plugin claimed, from the deformed vertices, shaded
 *  with glTF's material model by the environment and the lights, shadowed by the atlases
 *  `blackboard` holds once the frame is recorded (ShadowAtlases::readFinal). Where the frame
 *  has punctual lights, `opaque` draws the items without material layers into the surface
 *  targets, `lighting` shades each pixel they cover once and `opaque_layers` draws and shades
 *  the items with layers; else `opaque` draws and shades them all (OpaquePass.cpp). */
SceneTargets addOpaque(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                       SceneTargets scene, fg::BufferHandle vertices,
                       const fg::Blackboard& blackboard);
/** `lighting`: every pixel of `scene` a surface covers (its depth nearer than the clear's)
 *  shaded once from `surfaces` by the environment and the lights, shadowed by the atlases
 *  `blackboard` holds once the frame is recorded, added to its colour; returns the colour. */
fg::TextureHandle addLighting(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                              SceneTargets scene, SurfaceTargets surfaces,
                              const fg::Blackboard& blackboard);
/** `temporal`: the frame (`color`, jittered) blended into the history (TemporalHistory, its
 *  textures imported) by each pixel's motion (`motion`), rejected where what the pixel tracks
 *  changed, clipped to the frame's neighbourhood while anything moves; returns the resolved
 *  colour (the history's next), or with a debug view that view. */
fg::TextureHandle addTemporal(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                              TemporalHistory& history, fg::TextureHandle color,
                              fg::TextureHandle motion, fg::TextureHandle previousColor,
                              fg::TextureHandle previousMotion);
/** `tonemap`: exposure, ACES fit and sRGB (or the raw HDR colour) into `output`. */
void addTonemap(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                fg::TextureHandle scene, fg::TextureHandle output);

} // namespace render::passes
