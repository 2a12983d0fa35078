// What the refraction passes share: the frame's buffers and glass ids, the glass items drawn and
// the glass rectangle, the walk's uniforms, the capture's and the walk's programs.
#include "Passes.h"

#include "engine/deform/GpuDeformer.h"

#include "../Optics.h"

#include "engine/core/Log.h"
#include "engine/render/Environment.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

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
    buffers.distances = graph.importBuffer("refraction.distances", &gpu.glass);
    buffers.rectangle = graph.importBuffer("refraction.rectangle", &gpu.rectangle);
    buffers.layers = graph.importBuffer("refraction.layers", &gpu.layers);
    buffers.materials = graph.importBuffer("refraction.glass_materials", &gpu.glassMaterials);
    return buffers;
}

double GpuState::glassExtent(const scene::Character& character) {
    auto& [model, rest] = sides[character.model.get()];
    if (model.lock() != character.model) { // new, or another model at a freed one's address
        model = character.model;
        rest = restSides(*character.model);
    }
    return refraction::glassExtent(rest, character);
}

int GpuState::Glass::find(const Part& part) const {
    const auto at = std::find(parts.begin(), parts.end(), part);
    return at == parts.end() ? -1 : int(at - parts.begin());
}

SceneInputs sceneInputs(const fg::Blackboard& blackboard) {
    const auto* motion = blackboard.find<fg::TextureHandle>(plugin::kSceneMotion);
    return {blackboard.get<fg::TextureHandle>(plugin::kSceneColor),
            blackboard.get<fg::TextureHandle>(plugin::kSceneDepth),
            motion ? *motion : fg::TextureHandle{}};
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
    f.set("uTracedEntry", frame->temporal.enabled ? 1 : 0);
    f.set("uNormalLod", float(kNormalLod));
    f.set("uTirPolicy", reflect ? 1 : 0);
    f.set("uBounces", s.tirBounces);
    f.set("uFresnelMode", int(s.fresnel)); // 0 exact, 1 schlick, 2 off
    // Without opaque geometry the walk could only find the background, which is the
    // environment the lookup falls back to: skip it (the same image, cheaper).
    f.set("uNearby", s.nearby && frame->opaqueGeometry ? 1 : 0);
    f.set("uDebug", s.debug);
    f.set("uViewportSize", glm::vec2(frame->settings.size));
    f.set("uProjection", frame->camera.projection);
    f.set("uInverseProjection", glm::inverse(frame->camera.projection));
    f.set("uNear", frame->camera.znear);
    f.set("uFar", frame->camera.zfar);
    f.set("uNearbyDistance", 0.5f * (frame->camera.zfar - frame->camera.znear));
    const render::GroundPlane& ground = frame->ground;
    f.set("uGround", frame->settings.ground ? 1 : 0);
    f.set("uGroundPlane",
          glm::vec4(ground.height, ground.center.x, ground.center.z, ground.halfSize));
    const glm::mat4 viewToWorld = glm::inverse(frame->camera.view);
    f.set("uViewToWorld", glm::mat3(viewToWorld));
    f.set("uViewOriginWorld", glm::vec3(viewToWorld[3]));
    frame->environment->bind(f, frame->settings.environmentRotation,
                             frame->settings.environmentIntensity);
}

void FrameContext::drawGlassMaterials(const gl::Program& program,
                                      const gl::PipelineState& state) const {
    gl::bindStorage(slot::kGlassMaterials, gpu->glassMaterials);
    drawGlass(program, state, [this, &program](const render::DrawItem& item, std::size_t index) {
        program.set("uGlassId", gpu->glassIds[index]);
        item.materials->bind(program, *item.model, item.material);
    });
}

void FrameContext::drawGlass(
    const gl::Program& program, const gl::PipelineState& state,
    const std::function<void(const render::DrawItem&, std::size_t)>& perItem) const {
    program.use();
    program.set("uProjection", frame->camera.projection);
    render::setMotionUniforms(program, *frame);
    for (std::size_t index = 0; index < frame->items.size(); ++index) {
        const render::DrawItem& item = frame->items[index];
        if (!isGlass(item))
            continue;
        const glm::mat4 modelView = frame->camera.view * item.world;
        program.set("uModelView", modelView);
        program.set("uNormalMatrix", glm::inverseTranspose(glm::mat3(modelView)));
        program.set("uModel", item.world);
        program.set("uPreviousModel", item.previousWorld);
        gl::bindStorage(gl::slot::kVertices, *item.gpu->deformed);
        gl::bindStorage(gl::slot::kPreviousVertices,
                        item.gpu->previous ? *item.gpu->previous : *item.gpu->deformed);
        gl::bindStorage(gl::slot::kUvs, *item.gpu->uvs);
        // d_N: the BVH's values from this part's base.
        const GpuState::Glass& glass = gpu->glass;
        const int part = settings.usesNormalDistance() && glass.bvh
                             ? glass.find({item.key, item.instance, item.primitiveIndex})
                             : -1;
        program.set("uHasNormalDistance", part >= 0 ? 1 : 0);
        program.set("uDistanceBase", part >= 0 ? int(glass.bvh->base(std::size_t(part))) : 0);
        // Without d_N the binding still needs a buffer: the vertices stand in (unread).
        gl::bindStorage(slot::kNormalDistances,
                        part >= 0 ? glass.bvh->distances() : *item.gpu->deformed);
        if (perItem)
            perItem(item, index);
        gl::PipelineState itemState = state;
        itemState.clockwise = item.mirrored; // its front faces are its outward ones
        gl::apply(itemState);
        item.vertexArray->bind();
        gl::drawIndexed(item.gpu->indexCount);
    }
}

void FrameContext::growGlassRectangle() const {
    // Empty: min > max (ints for the rectangle, floats as ordered ints for the box).
    using R = GlassRectangleGpu;
    gpu->rectangle.fill(offsetof(R, pixelMin), 2, std::uint32_t(INT32_MAX));
    gpu->rectangle.fill(offsetof(R, pixelMax), 2, std::uint32_t(INT32_MIN));
    gpu->rectangle.fill(offsetof(R, boxMin), 3, std::uint32_t(INT32_MAX));
    gpu->rectangle.fill(offsetof(R, boxMax), 3, std::uint32_t(INT32_MIN));
    gpu->rectangle.fill(offsetof(R, overflowPixels), 1, 0u);
    gpu->rectangle.fill(offsetof(R, backRange), 1, 0x7F7FFFFFu); // FLT_MAX
    gpu->rectangle.fill(offsetof(R, backRange) + 4, 1, 0u);
    gpu->rectangle.fill(offsetof(R, frontMin), 1, 0x7F7FFFFFu);
    gpu->rectangle.fill(offsetof(R, traceRays), 10, 0u); // the trace's and the hybrid's counts
    gpu->rectangleGrow.use();
    gpu->rectangleGrow.set("uViewportSize", glm::vec2(frame->settings.size));
    gl::bindStorage(slot::kGlassRectangle, gpu->rectangle);
    for (const render::DrawItem& item : frame->items) {
        if (!isGlass(item))
            continue;
        gpu->rectangleGrow.set("uModelViewProjection", frame->camera.viewProjection() * item.world);
        gpu->rectangleGrow.set("uModelView", frame->camera.view * item.world);
        const int count = int(item.primitive->vertexCount());
        gpu->rectangleGrow.set("uVertexCount", count);
        gl::bindStorage(gl::slot::kVertices,
                        item.geometry->cage(item.instance, item.primitiveIndex).vertices);
        gl::dispatch(std::uint32_t((count + 63) / 64));
    }
    gl::memoryBarrier(gl::BarrierStorage);
}

void FrameContext::drawMaskedRectangle(gl::Blend blend) const {
    // The rectangle lies at depth 1: it passes only where the mask holds less.
    gl::apply({.cull = gl::Cull::None,
               .depthWrite = false,
               .depthFunc = gl::DepthFunc::Greater,
               .blend = blend});
    drawRectangle();
}

void FrameContext::drawRectangle() const {
    gl::bindStorage(slot::kGlassRectangle, gpu->rectangle);
    gpu->emptyVao.bind();
    gl::drawArrays(6);
}

void FrameContext::setLayerUniforms(const gl::Program& program) const {
    const glm::ivec2 size = frame->settings.size;
    program.set("uPixelCount", size.x * size.y);
    program.set("uViewportWidth", size.x);
    program.set("uViewportSize", glm::vec2(size));
    program.set("uKeyNear", frame->camera.znear);
    program.set("uKeyLogRange", std::log2(frame->camera.zfar / frame->camera.znear));
    const GpuState::LayerStorage& layers = gpu->layers;
    gl::bindStorage(slot::kLayerHeads, layers.heads);
    gl::bindStorage(slot::kLayerDepths, layers.depths);
    gl::bindStorage(slot::kLayerAttrs, layers.attrs);
    if (texturedGlass)
        gl::bindStorage(slot::kLayerSurfaces, layers.surfaces);
    gl::bindStorage(slot::kLayerMotions, layers.motions);
    gl::bindStorage(slot::kGlassMaterials, gpu->glassMaterials);
    render::setMotionUniforms(program, *frame);
}

core::Status walkPrograms(GpuState& gpu, FrameContext& c) {
    const bool pair = !c.settings.layered();
    const int capacity = pair ? 2 : c.settings.layerCapacity;
    const bool textures = c.texturedGlass;
    const std::string texturesDefine = std::string("GLASS_TEXTURES ") + (textures ? "1" : "0");
    // The trace with several samples (or one a frame of a frame that accumulates) reads the
    // textures at their entries as at every hit, at their base level (converging to the
    // reference); with one, filtered like the walk (a pixel's texels averaged, its frame closer
    // to the reference's many rays than one texel).
    const bool baseLevel = c.settings.method == Settings::Method::Trace &&
                           (c.settings.addsSamples() || c.frame->temporal.enabled);
    if (!pair && gpu.layerPrograms != std::tuple{capacity, textures, baseLevel}) {
        const std::vector<std::string> defines{
            "LAYER_CAPACITY " + std::to_string(capacity), texturesDefine,
            std::string("TEXTURES_BASE_LEVEL ") + (baseLevel ? "1" : "0")};
        auto capture = gl::Program::graphics(*c.frame->shaders, "refraction/glass.vert.glsl",
                                             "refraction/layers_capture.frag.glsl", defines);
        if (!capture)
            return capture.error();
        auto resolve = gl::Program::graphics(*c.frame->shaders, "refraction/rectangle.vert.glsl",
                                             "refraction/layers_resolve.frag.glsl", defines);
        if (!resolve)
            return resolve.error();
        gpu.layersCapture = std::move(*capture);
        gpu.layersResolve = std::move(*resolve);
        gpu.layerPrograms = {capacity, textures, baseLevel};
    }
    if (pair && gpu.pairPrograms != int(textures)) {
        auto surface = gl::Program::graphics(*c.frame->shaders, "refraction/glass.vert.glsl",
                                             "refraction/surface.frag.glsl", {texturesDefine});
        if (!surface)
            return surface.error();
        auto resolve = gl::Program::graphics(
            *c.frame->shaders, "refraction/rectangle.vert.glsl", "refraction/resolve.frag.glsl",
            {"LAYER_CAPACITY 2", "PAIR_GATHERED 0", texturesDefine});
        if (!resolve)
            return resolve.error();
        gpu.surface = std::move(*surface);
        gpu.resolve[0] = std::move(*resolve);
        gpu.pairPrograms = int(textures);
    }
    // Dispersion: none in this frame, or the dispersion search's.
    const bool dispersion =
        std::any_of(c.gpu->glassOptics.begin(), c.gpu->glassOptics.end(),
                    [](const GlassMaterialGpu& m) { return m.ior.r != m.ior.b; });
    const int mode = dispersion ? int(c.settings.dispersionSearch) : Settings::kNoDispersion;
    const bool lit = c.lit();
    const int captureKey = pair ? 0 : capacity; // the pair, or K layers
    auto key = [&](Settings::Method method) {
        return GpuState::WalkKey{captureKey, int(method), mode, lit, textures};
    };
    auto walkDefines = [&](Settings::Method method) {
        return std::vector<std::string>{"LAYER_CAPACITY " + std::to_string(capacity),
                                        std::string("CAPTURE_PAIR ") + (pair ? "1" : "0"),
                                        "LAYER_DISPERSION " + std::to_string(mode),
                                        std::string("PUNCTUAL_LIGHTS ") + (lit ? "1" : "0"),
                                        texturesDefine,
                                        "LAYER_METHOD " + std::to_string(int(method)),
                                        std::string("HYBRID_LIST ") +
                                            (method == Settings::Method::Hybrid ? "1" : "0")};
    };
    if (!gpu.walkPrograms.count(key(c.settings.method))) {
        // Every method's variant at once: switching methods (the viewer's panel) then compiles
        // nothing, and the live programs do not depend on which methods ran.
        for (const Settings::Method method :
             {Settings::Method::Sir, Settings::Method::Isr, Settings::Method::Dir,
              Settings::Method::Trace, Settings::Method::Hybrid}) {
            auto walk = gl::Program::graphics(*c.frame->shaders, "refraction/rectangle.vert.glsl",
                                              "refraction/walk.frag.glsl", walkDefines(method));
            if (!walk)
                return walk.error();
            gpu.walkPrograms.insert_or_assign(key(method), std::move(*walk));
        }
    }
    c.walk = &gpu.walkPrograms.at(key(c.settings.method));
    if (c.settings.method != Settings::Method::Hybrid)
        return {};
    // The hybrid's trace pass: the walk as the trace's variant, over the handed-over pixels,
    // storing the format of the walk's target.
    const bool addsUp = c.settings.addsSamples();
    const auto traceKey = std::pair{key(Settings::Method::Hybrid), addsUp};
    if (!gpu.handedOverTrace.count(traceKey)) {
        std::vector<std::string> defines = walkDefines(Settings::Method::Trace);
        defines.back() = "HYBRID_LIST 1"; // the trace's walk, over the hybrid's list
        defines.push_back(std::string("SHADED_FORMAT ") + (addsUp ? "rgba32f" : "rgba16f"));
        auto trace =
            gl::Program::compute(*c.frame->shaders, "refraction/walk_trace.comp.glsl", defines);
        if (!trace)
            return trace.error();
        gpu.handedOverTrace.insert_or_assign(traceKey, std::move(*trace));
    }
    c.handedOverTrace = &gpu.handedOverTrace.at(traceKey);
    return {};
}

void ensureLayerStorage(GpuState::LayerStorage& layers, glm::ivec2 size, int capacity,
                        int surfaceSlots, bool motions) {
    const std::size_t pixels = std::size_t(size.x) * std::size_t(size.y);
    const std::size_t motionBytes =
        motions ? pixels * std::size_t(capacity) * sizeof(std::uint32_t) : sizeof(std::uint32_t);
    if (layers.motions.size() != motionBytes)
        layers.motions = gl::Buffer(motionBytes);
    const std::size_t layerBytes = 2 * sizeof(std::uint32_t) * pixels;
    const std::size_t surfaceBytes = layerBytes * std::size_t(surfaceSlots);
    if (layers.surfaces.size() != surfaceBytes)
        layers.surfaces = surfaceSlots > 0 ? gl::Buffer(surfaceBytes) : gl::Buffer();
    layers.surfaceSlots = surfaceSlots;
    if (layers.size == size && layers.capacity == capacity)
        return;
    layers.heads = gl::Buffer(pixels * 3 * sizeof(std::uint32_t));
    layers.depths = gl::Buffer(pixels * layerDepthSlots(capacity) * sizeof(float));
    layers.attrs = gl::Buffer(layerBytes * std::size_t(capacity));
    layers.size = size;
    layers.capacity = capacity;
}

std::size_t layerDepthSlots(int capacity) {
    return (std::size_t(capacity) + 3) / 4 * 4;
}

std::size_t layerBytesPerPixel(int capacity, bool outlines, int surfaceSlots) {
    // The arrays (head, depth slots, attributes, surfaces), the depth maps the resolve pass
    // writes, and the nearest layers' map the outline pass reads.
    const std::size_t layer = 2 * sizeof(std::uint32_t);
    return 3 * sizeof(std::uint32_t) + layerDepthSlots(capacity) * sizeof(float) +
           std::size_t(capacity + surfaceSlots) * layer +
           layerDepthSlots(capacity) * sizeof(float) + (outlines ? sizeof(float) : 0);
}

namespace {

/** `map` of `item`'s model as a texture the trace reads (among the first
 *  slot::kTracedTextures.count distinct ones of the frame; past them: a warning, and traced
 *  hits go without it). */
TracedTextureGpu tracedTexture(FrameContext& c, const render::DrawItem& item,
                               const scene::TextureRef& map, bool colour) {
    TracedTextureGpu traced;
    const gl::Texture* texture = map.present() ? (colour ? item.materials->srgb(map.texture)
                                                         : item.materials->linear(map.texture))
                                               : nullptr;
    if (!texture)
        return traced;
    auto& textures = c.gpu->tracedTextures;
    auto at = std::find(textures.begin(), textures.end(), texture);
    if (at == textures.end() && textures.size() < slot::kTracedTextures.count)
        at = textures.insert(textures.end(), texture);
    if (at == textures.end()) {
        if (!c.gpu->warnedTracedTextures)
            core::logWarning("refraction: more than " +
                             std::to_string(slot::kTracedTextures.count) +
                             " glass textures in one frame; the trace meets the others' "
                             "surfaces without them");
        c.gpu->warnedTracedTextures = true;
        return traced;
    }
    traced.unit = std::int32_t(at - textures.begin());
    traced.uvSet = map.texCoord;
    traced.row0 = {map.transform[0][0], map.transform[1][0], map.transform[2][0]};
    traced.row1 = {map.transform[0][1], map.transform[1][1], map.transform[2][1]};
    return traced;
}

/** The optics of glass id `item` (its character's glass extent `extent`, solid `solid`). */
GlassMaterialGpu glassMaterial(FrameContext& c, const render::DrawItem& item, double extent,
                               int solid) {
    const scene::Material* m =
        item.material >= 0 ? &item.model->materials[std::size_t(item.material)] : nullptr;
    const Optics o = opticsFor(c.settings, m, item.source->overrides, extent);
    GlassMaterialGpu g{};
    g.ior = o.ior;
    g.transmission = o.transmission;
    g.sigma = o.sigma;
    g.roughness = o.roughness;
    g.baseColor = glm::vec3(o.baseColor);
    g.metallic = o.metallic;
    g.emissive = m ? m->emissiveFactor * m->emissiveStrength : glm::vec3(0.0f);
    g.solid = std::uint32_t(solid);
    g.specularColor = o.specularColor;
    g.specularWeight = o.specularWeight;
    g.sheenColor = o.sheenColor;
    g.sheenRoughness = o.sheenRoughness;
    g.clearcoat = o.clearcoat;
    g.clearcoatRoughness = o.clearcoatRoughness;
    g.iridescence = o.iridescence;
    g.iridescenceIor = o.iridescenceIor;
    g.filmThickness = o.iridescenceThickness;
    g.authored = m && m->isTransmissive() ? 1u : 0u;
    if (!m)
        return g;
    g.normalScale = m->normalTexture.scale;
    g.normalTexture = tracedTexture(c, item, m->normalTexture, false);
    g.baseColorTexture = tracedTexture(c, item, m->baseColorTexture, true);
    if (g.authored) {
        g.metallicRoughnessTexture = tracedTexture(c, item, m->metallicRoughnessTexture, false);
        g.transmissionTexture = tracedTexture(c, item, m->transmissionTexture, false);
    }
    return g;
}

/** Whether the surface of glass `g` varies over it: a texture that the capture reads for the
 *  walk (the normal map aside, which it reads anyway). */
bool textured(const scene::Material* m) {
    return m && (m->baseColorTexture.present() ||
                 (m->isTransmissive() &&
                  (m->transmissionTexture.present() || m->metallicRoughnessTexture.present())));
}

} // namespace

void assignGlassIds(FrameContext& c) {
    const auto& items = c.frame->items;
    c.gpu->glassIds.assign(items.size(), -1);
    c.gpu->glassOptics.clear();
    c.gpu->tracedTextures.clear();
    c.texturedGlass = false;
    std::map<std::pair<std::uint64_t, int>, int> ids;
    std::map<std::uint64_t, int> solids; // a character's glass is one solid (the media rule)
    bool full = false;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const render::DrawItem& item = items[i];
        if (!c.isGlass(item))
            continue;
        const auto key = std::pair{item.key, item.material};
        if (const auto known = ids.find(key); known != ids.end()) {
            c.gpu->glassIds[i] = known->second;
            continue;
        }
        if (c.gpu->glassOptics.size() == kMaxGlassIds) {
            full = true;
            c.gpu->glassIds[i] = int(kMaxGlassIds) - 1;
            continue;
        }
        const int solid = solids.emplace(item.key, int(solids.size())).first->second;
        c.gpu->glassOptics.push_back(
            glassMaterial(c, item, c.gpu->glassExtent(*item.source), solid));
        c.texturedGlass =
            c.texturedGlass ||
            textured(item.material >= 0 ? &item.model->materials[std::size_t(item.material)]
                                        : nullptr);
        ids.emplace(key, int(c.gpu->glassOptics.size()) - 1);
        c.gpu->glassIds[i] = int(c.gpu->glassOptics.size()) - 1;
    }
    if (full && !c.gpu->warnedGlassIds) {
        core::logWarning("refraction: more than 255 glass materials (character x material) in "
                         "one frame; the layered path draws the rest with the 255th's optics");
        c.gpu->warnedGlassIds = true;
    }
}

} // namespace refraction
