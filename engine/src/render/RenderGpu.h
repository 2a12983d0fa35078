// The renderer's GPU objects, shared by its passes (render/passes/): the world's models and
// characters on the GPU, the frame's draw items, environment and the framebuffer
// they draw with.
#pragma once

#include "engine/anim/Pose.h"
#include "engine/deform/GpuDeformer.h"
#include "engine/gl/Commands.h"
#include "engine/gl/Framebuffer.h"
#include "engine/gl/Program.h"
#include "engine/render/Environment.h"
#include "engine/render/FrameInfo.h"
#include "engine/render/Lighting.h"
#include "engine/render/MaterialTextures.h"

#include "TemporalHistory.h"

#include <map>
#include <memory>
#include <vector>

namespace render {

/** A model on the GPU, shared by every character that places it. */
struct ModelGpu {
    std::shared_ptr<const scene::Model> model;
    std::shared_ptr<const deform::GpuModel> upload;
    std::shared_ptr<MaterialTextures> materials; ///< kept when the level changes
    std::vector<int> lightNodes; ///< nodes with a KHR_lights_punctual light (render::lightNodes)
    /** Per clip (-1: the rest pose): the bounds of its deformed meshes over the clip, which the
     *  shadow views are fitted to (performanceBounds(), computed when a frame first plays the
     *  clip). */
    std::map<int, Bounds> clipBounds;
    /** Per mesh, per primitive: a vertex array binding its index buffer (the same for every
     *  node, instance and placement that draws the mesh; empty for meshes no node draws). */
    std::vector<std::vector<gl::VertexArray>> vertexArrays;
};

/** A character on the GPU: its placement of the model and its reused pose. */
struct CharacterGpu {
    std::shared_ptr<ModelGpu> model;
    std::unique_ptr<deform::GpuDeformer> deformer;
    anim::Pose pose;
};

struct RenderGpu {
    std::vector<std::shared_ptr<ModelGpu>> models;      // the prepared world's, each once
    std::vector<std::shared_ptr<ModelGpu>> modelsInUse; // Renderer::prepare()'s scratch
    std::vector<CharacterGpu> characters;               // the prepared world's, in its order
    deform::PoseUpload poses;                           // every character's, this frame
    std::vector<DrawItem> items;                        // this frame's (storage reused)
    std::vector<scene::PlacedLight> lights;             // this frame's, in world space
    LightingBuffer lighting;                            // the lights (gl::slot::kLighting)
    ShadowPlan shadows;                                 // this frame's shadow views
    std::size_t reportedOverLimit = 0; ///< lights over the shadow limit last warned of
    /** Reads the shadow depth atlas as a shadow sampler (compared, bilinear). */
    gl::Sampler shadowSampler{gl::Filter::Linear, gl::Wrap::Clamp, true};
    /** What the shadow units hold in frames where no light casts: nothing in front. */
    gl::Texture noShadowDepth, noShadowGlass;
    /** What the caustics unit holds where no plugin focuses light (every frame until one
     *  binds its own): no receiver anywhere (kNoGlass), so light through glass goes straight. */
    gl::Texture noCaustics;
    std::unique_ptr<Environment> environment;
    TemporalHistory history;
    /** The sets of layers the prepared models' materials use (Material::surfaceLayers()): the
     *  opaque pass's variants. */
    std::vector<int> layerSets;
    gl::VertexArray emptyVao;
    gl::Framebuffer framebuffer;
};

} // namespace render
