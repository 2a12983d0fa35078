// What the refraction passes share: the textures' descriptors, the frame's buffers imported,
// the uniforms the walk and the layers' passes set, the glass items and the glass rectangle
// drawn, and the walk's inputs, which the hybrid's trace reads too.
#include "Passes.h"

#include "engine/deform/GpuDeformer.h"
#include "engine/render/Environment.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace refraction {

gl::TextureDesc colorDesc(glm::ivec2 size) {
    return {size, gl::Format::RGBA16F, 1};
}
gl::TextureDesc walkDesc(glm::ivec2 size, const Settings& settings) {
    return {size, settings.addsSamples() ? gl::Format::RGBA32F : gl::Format::RGBA16F, 1};
}
gl::TextureDesc normalDesc(glm::ivec2 size) {
    return {size, gl::Format::RGBA16F, kNormalLod + 1};
}
gl::TextureDesc zDesc(glm::ivec2 size) {
    return {size, gl::Format::Depth32F, 1};
}

FrameBuffers importBuffers(fg::FrameGraph& graph, const fg::Blackboard& blackboard, GpuState& gpu) {
    FrameBuffers buffers;
    buffers.vertices = blackboard.get<fg::BufferHandle>(plugin::kSceneVertices);
    buffers.bvh = graph.importBuffer("refraction.bvh", &gpu.glass);
    buffers.counters = graph.importBuffer("refraction.counters", gpu.counters);
    buffers.materials = graph.importBuffer("refraction.glass_materials", gpu.glassMaterials);
    return buffers;
}

GpuState::Glass& glassBvh(const fg::Resources& r, fg::BufferHandle bvh) {
    return *static_cast<GpuState::Glass*>(r.object(bvh));
}

GlassDrawn readGlassDrawn(fg::Builder& b, const FrameContext& c, const FrameBuffers& buffers) {
    b.read(buffers.vertices); // drawn from the deformed vertices (DrawItem::gpu)
    GlassDrawn glass{b.read(buffers.materials), {}};
    if (c.settings.usesNormalDistance())
        glass.bvh = b.read(buffers.bvh);
    return glass;
}

SceneInputs sceneInputs(const fg::Blackboard& blackboard) {
    const auto* motion = blackboard.find<fg::TextureHandle>(plugin::kSceneMotion);
    const auto* historyColor = blackboard.find<fg::TextureHandle>(plugin::kHistoryColor);
    const auto* history = blackboard.find<fg::TextureHandle>(plugin::kHistoryMotion);
    return {blackboard.get<fg::TextureHandle>(plugin::kSceneColor),
            blackboard.get<fg::TextureHandle>(plugin::kSceneDepth),
            motion ? *motion : fg::TextureHandle{},
            historyColor ? *historyColor : fg::TextureHandle{},
            history ? *history : fg::TextureHandle{},
            render::ShadowAtlases::of(blackboard),
            fg::TextureHandle{}};
}

void FrameContext::setWalkUniforms(const gl::Program& f) const {
    const Settings& s = settings;
    f.use();
    f.set("uSteps", s.searchSteps);
    f.set("uMarchSteps", s.marchSteps);
    f.set("uInterfaces", s.interfaces);
    f.set("uHybridCriteria", s.hybridCriteria);
    f.set("uTraceSamples", s.traceSamples);
    // A frame that accumulates takes one sample a pixel, seeded by its index: the trace's paths
    // sampled on still frames (which converge to the reference), deterministic while moving.
    f.set("uSampled", s.traceSamples > 1 || frame->temporal.still ? 1 : 0);
    f.set("uFrameSeed", int(frame->temporal.index));
    f.set("uFrameJitter", frame->temporal.jitter); // zero where the frame does not accumulate
    f.set("uTracedEntry", frame->temporal.enabled ? 1 : 0);
    f.set("uFreshSamples", freshSamples() > 1 ? freshSamples() : 0);
    f.set("uFreshContrast", float(s.freshContrast));
    f.set("uNormalLod", float(kNormalLod));
    f.set("uTirPolicy", reflect ? 1 : 0);
    f.set("uBounces", s.tirBounces);
    f.set("uFresnelMode", int(s.fresnel)); // 0 exact, 1 schlick, 2 off
    f.set("uDebug", s.debug);
    f.set("uViewportSize", glm::vec2(frame->settings.size));
    f.set("uProjection", frame->camera.projection);
    f.set("uInverseProjection", glm::inverse(frame->camera.projection));
    f.set("uNear", frame->camera.znear);
    f.set("uFar", frame->camera.zfar);
    f.set("uNearbyDistance", 0.5f * (frame->camera.zfar - frame->camera.znear));
    f.set("uSceneTileLevels", sceneTiles().levels);
    const render::GroundPlane& ground = frame->ground;
    f.set("uGroundPlane",
          glm::vec4(ground.height, ground.center.x, ground.center.z, ground.halfSize));
    const glm::mat4 viewToWorld = glm::inverse(frame->camera.view);
    f.set("uViewToWorld", glm::mat3(viewToWorld));
    f.set("uViewOriginWorld", glm::vec3(viewToWorld[3]));
    frame->environment->bind(f, frame->settings.environmentRotation,
                             frame->settings.environmentIntensity);
}

void FrameContext::drawGlassMaterials(const gl::Program& program, const gl::PipelineState& state,
                                      const fg::Resources& r, const GlassDrawn& glass,
                                      const std::optional<GlassView>& from) const {
    gl::bindStorage(slot::kGlassMaterials, r.buffer(glass.materials));
    drawGlass(
        program, state, r, glass,
        [this, &program](const render::DrawItem& item, std::size_t index) {
            program.set("uGlassId", gpu->glassIds[index]);
            item.materials->bind(program, item.values);
        },
        from);
}

void FrameContext::drawGlass(
    const gl::Program& program, const gl::PipelineState& state, const fg::Resources& r,
    const GlassDrawn& glass,
    const std::function<void(const render::DrawItem&, std::size_t)>& perItem,
    const std::optional<GlassView>& from) const {
    const GlassView v = from ? *from : cameraView();
    const GpuState::Glass* bvh = glass.bvh.valid() ? &glassBvh(r, glass.bvh) : nullptr;
    program.use();
    program.set("uProjection", v.projection);
    render::setMotionUniforms(program, *frame);
    for (std::size_t index = 0; index < frame->items.size(); ++index) {
        const render::DrawItem& item = frame->items[index];
        if (!isGlass(item))
            continue;
        const glm::mat4 modelView = v.view * item.world;
        program.set("uModelView", modelView);
        program.set("uNormalMatrix", glm::inverseTranspose(glm::mat3(modelView)));
        program.set("uModel", item.world);
        program.set("uPreviousModel", item.previousWorld);
        gl::bindStorage(gl::slot::kVertices, *item.gpu->deformed);
        gl::bindStorage(gl::slot::kPreviousVertices,
                        item.gpu->previous ? *item.gpu->previous : *item.gpu->deformed);
        gl::bindStorage(gl::slot::kUvs, *item.gpu->uvs);
        // d_N: the BVH's values from this part's base.
        const int part =
            bvh && bvh->bvh ? bvh->find({item.key, item.instance, item.primitiveIndex}) : -1;
        program.set("uHasNormalDistance", part >= 0 ? 1 : 0);
        program.set("uDistanceBase", part >= 0 ? int(bvh->bvh->base(std::size_t(part))) : 0);
        // Without d_N the binding still needs a buffer: the vertices stand in (unread).
        gl::bindStorage(slot::kNormalDistances,
                        part >= 0 ? bvh->bvh->distances() : *item.gpu->deformed);
        if (perItem)
            perItem(item, index);
        gl::PipelineState itemState = state;
        itemState.clockwise = item.mirrored; // its front faces are its outward ones
        gl::apply(itemState);
        item.vertexArray->bind();
        gl::drawIndexed(item.gpu->indexCount);
    }
}

void FrameContext::drawMaskedRectangle(const gl::Buffer& extent, gl::Blend blend) const {
    // The rectangle lies at depth 1: it passes only where the mask holds less.
    gl::apply({.cull = gl::Cull::None,
               .depthWrite = false,
               .depthFunc = gl::DepthFunc::Greater,
               .blend = blend});
    drawRectangle(extent);
}

void FrameContext::drawRectangle(const gl::Buffer& extent) const {
    gl::bindStorage(slot::kGlassExtent, extent);
    gpu->emptyVao.bind();
    gl::drawArrays(6);
}

void FrameContext::setLayerUniforms(const gl::Program& program, const fg::Resources& r,
                                    const LayerBuffers& layers) const {
    const glm::ivec2 size = frame->settings.size;
    program.set("uPixelCount", size.x * size.y);
    program.set("uViewportWidth", size.x);
    program.set("uViewportSize", glm::vec2(size));
    program.set("uKeyNear", frame->camera.znear);
    program.set("uKeyLogRange", std::log2(frame->camera.zfar / frame->camera.znear));
    gl::bindStorage(slot::kLayerHeads, r.buffer(layers.heads));
    gl::bindStorage(slot::kLayerDepths, r.buffer(layers.depths));
    gl::bindStorage(slot::kLayerAttrs, r.buffer(layers.attrs));
    if (layers.surfaces.valid())
        gl::bindStorage(slot::kLayerSurfaces, r.buffer(layers.surfaces));
    gl::bindStorage(slot::kLayerMotions, r.buffer(layers.motions));
    render::setMotionUniforms(program, *frame);
}

int FrameContext::traceSamples() const {
    return frame->temporal.enabled ? 1 : settings.traceSamples;
}

int FrameContext::freshSamples() const {
    const render::TemporalFrame& t = frame->temporal;
    const bool moving = t.enabled && !t.still && t.index > 0;
    return moving && settings.freshSampled() && settings.debug == 0 ? settings.freshSamples : 1;
}

bool FrameContext::severalSamples() const {
    return settings.traces() && (traceSamples() > 1 || freshSamples() > 1);
}

bool FrameContext::seesNearbyScene() const {
    // Without opaque geometry the walk could only find the background, which is the
    // environment the lookup falls back to: left out (the same image, cheaper).
    return settings.nearby && frame->opaqueGeometry;
}

bool FrameContext::marchesScene() const {
    return seesNearbyScene() && settings.method != Settings::Method::Trace;
}

gl::TextureDesc FrameContext::sceneTiles() const {
    const glm::ivec2 tiles = (frame->settings.size + 3) / 4;
    int levels = 1;
    while (levels < 6 && std::max(tiles.x, tiles.y) >> levels > 0)
        ++levels;
    return {tiles, gl::Format::R32F, levels};
}

WalkInputs readWalkInputs(fg::Builder& b, const FrameContext& c, const FrameBuffers& buffers,
                          const SceneInputs& scene, const Capture& capture) {
    WalkInputs in;
    in.extent = b.read(buffers.extent);
    in.layers = readLayers(b, buffers.layers);
    in.materials = b.read(buffers.materials);
    if (!c.settings.layered())
        in.pairRanges = b.read(buffers.pairRanges);
    if (c.settings.traces())
        in.bvh = b.read(buffers.bvh);
    for (auto [from, to] : {std::pair{capture.mask, &in.capture.mask},
                            std::pair{capture.depths0, &in.capture.depths0},
                            std::pair{capture.depths1, &in.capture.depths1},
                            std::pair{capture.normals[0], &in.capture.normals[0]},
                            std::pair{capture.normals[1], &in.capture.normals[1]}})
        if (from.valid())
            *to = b.read(from);
    in.sceneColor = b.read(scene.color);
    in.sceneDepth = b.read(scene.depth);
    if (scene.depthTiles.valid())
        in.sceneDepthTiles = b.read(scene.depthTiles);
    in.shadows = scene.shadows.read(b);
    return in;
}

core::Status bindWalkInputs(const fg::Resources& r, const FrameContext& c, const WalkInputs& in,
                            fg::BufferHandle counters) {
    gl::bindStorage(slot::kGlassExtent, r.buffer(in.extent));
    if (in.pairRanges.valid())
        gl::bindStorage(slot::kPairRanges, r.buffer(in.pairRanges));
    gl::bindStorage(slot::kGlassMaterials, r.buffer(in.materials));
    gl::bindStorage(slot::kWalkCounters, r.buffer(counters));
    gl::bindTexture(slot::kSceneColor, r.texture(in.sceneColor));
    gl::bindTexture(slot::kSceneDepth, r.texture(in.sceneDepth));
    in.shadows.bind(r, *c.frame->shadowSampler);
    if (in.sceneDepthTiles.valid())
        gl::bindTexture(slot::kSceneDepthTiles, r.texture(in.sceneDepthTiles));
    // The layer depth maps (layers.glsl), the pair's normals; an absent map: the first depth
    // map stands in, or without maps (SIR's walk) the scene's colour (unread).
    const auto present = [&](fg::TextureHandle h) -> const gl::Texture& {
        return r.texture(h.valid()                    ? h
                         : in.capture.depths0.valid() ? in.capture.depths0
                                                      : in.sceneColor);
    };
    gl::bindTexture(slot::kLayerDepthMaps, present(in.capture.depths0), 0);
    gl::bindTexture(slot::kLayerDepthMaps, present(in.capture.depths1), 1);
    gl::bindTexture(slot::kPairNormals, present(in.capture.normals[0]), 0);
    gl::bindTexture(slot::kPairNormals, present(in.capture.normals[1]), 1);
    if (!c.settings.traces())
        return {};
    const GpuState::Glass& glass = glassBvh(r, in.bvh);
    if (!glass.bvh)
        return core::Error{"refraction: the trace has no glass BVH"};
    glass.bvh->bindForTraversal();
    bindTracedTextures(*c.gpu);
    return {};
}

void bindHistory(const fg::Resources& r, fg::TextureHandle color, fg::TextureHandle motion) {
    gl::bindTexture(gl::slot::kHistory, r.texture(color), 0);
    gl::bindTexture(gl::slot::kHistory, r.texture(motion), 1);
}

void bindTracedTextures(const GpuState& gpu) {
    // The first stands in for absent ones (unread).
    const auto& textures = gpu.tracedTextures;
    for (std::uint32_t i = 0; i < slot::kTracedTextures.count && !textures.empty(); ++i)
        gl::bindTexture(slot::kTracedTextures,
                        *textures[std::min<std::size_t>(i, textures.size() - 1)], i);
}

} // namespace refraction
