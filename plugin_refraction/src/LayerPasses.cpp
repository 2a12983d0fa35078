// The layered path (ARCHITECTURE.md, "How a ray walks the layers"): every glass item of every
// character drawn once into per-pixel layer arrays (layers_capture.frag.glsl), then one pass
// over the glass pixels walks them (layers_shade.frag.glsl).
#include "FramePasses.h"

#include "Optics.h"

#include "engine/core/Log.h"
#include "engine/render/MaterialTextures.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>

namespace refraction {
namespace {

/** Glass ids a layer can name (8 bits, layers.glsl, less the walk's 0 for air). */
constexpr std::size_t kMaxGlassIds = 255;
// Texture units: 0-1 the environment, 2-3 the scene colour and depth, 4-5 the layer depth maps,
// 6 the outline pass's nearest layers, 8-14 the material's.
constexpr int kSceneColorUnit = 2, kSceneDepthUnit = 3, kLayerDepthUnit = 4, kSurfaceUnit = 6,
              kMaterialUnit = 8;
constexpr float kNoLayer = 3.0e38f; // layers.glsl: an unused depth

gl::TextureDesc colorDesc(glm::ivec2 size) {
    return {size, gl::Format::RGBA16F, 1};
}

/** Depth slots per pixel: whole vec4s (layers.glsl reads four at once). */
std::size_t depthSlots(int capacity) {
    return (std::size_t(capacity) + 3) / 4 * 4;
}

/** The layer arrays for `size` and capacity K, reallocated only when either changes. */
void ensureLayerStorage(GpuState::LayerStorage& layers, glm::ivec2 size, int capacity) {
    if (layers.size == size && layers.capacity == capacity)
        return;
    const std::size_t pixels = std::size_t(size.x) * std::size_t(size.y);
    layers.heads = gl::Buffer(pixels * 3 * sizeof(std::uint32_t));
    layers.depths = gl::Buffer(pixels * depthSlots(capacity) * sizeof(float));
    layers.attrs = gl::Buffer(pixels * std::size_t(capacity) * 2 * sizeof(std::uint32_t));
    layers.size = size;
    layers.capacity = capacity;
}

/** The uniforms of layers.glsl. */
void setLayerUniforms(const FrameContext& c, const gl::Program& program) {
    const glm::ivec2 size = c.frame->settings.size;
    program.set("uPixelCount", size.x * size.y);
    program.set("uViewportWidth", size.x);
    program.set("uViewportSize", glm::vec2(size));
    program.set("uKeyNear", c.frame->camera.znear);
    program.set("uKeyLogRange", std::log2(c.frame->camera.zfar / c.frame->camera.znear));
    const GpuState::LayerStorage& layers = c.gpu->layers;
    gl::bindStorage(5, layers.heads);
    gl::bindStorage(6, layers.depths);
    gl::bindStorage(7, layers.attrs);
    gl::bindStorage(8, c.gpu->glassMaterials);
}

/** The layer depth maps as uLayerDepths0/1 (layers.glsl); an absent second map: the first
 *  stands in. */
void bindLayerDepthMaps(const gl::Program& program, const fg::Resources& r,
                        fg::TextureHandle depths0, fg::TextureHandle depths1) {
    for (int map = 0; map < 2; ++map) {
        const fg::TextureHandle depths = map == 1 && depths1.valid() ? depths1 : depths0;
        gl::bindTexture(std::uint32_t(kLayerDepthUnit + map), r.texture(depths));
        program.set(map == 0 ? "uLayerDepths0" : "uLayerDepths1", kLayerDepthUnit + map);
    }
}

} // namespace

core::Result<const gl::Program*> layerShadeProgram(GpuState& gpu, const FrameContext& c) {
    if (gpu.layerProgramsCapacity != c.settings.layerCapacity) {
        gpu.layerShadePrograms.clear();
        const std::vector<std::string> defines{"LAYER_CAPACITY " +
                                               std::to_string(c.settings.layerCapacity)};
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
        gpu.layerProgramsCapacity = c.settings.layerCapacity;
    }
    // Dispersion: 0 none in this frame, 1 shared search, 2 per channel.
    const bool dispersion =
        std::any_of(c.gpu->glassOptics.begin(), c.gpu->glassOptics.end(),
                    [](const GlassMaterialGpu& m) { return m.ior.r != m.ior.b; });
    const int mode = !dispersion                                                         ? 0
                     : c.settings.dispersionSearch == Settings::DispersionSearch::Shared ? 1
                                                                                         : 2;
    const std::pair key{int(c.settings.method), mode};
    if (!gpu.layerShadePrograms.count(key)) {
        // Every method's variant at once: switching methods (the viewer's panel) then compiles
        // nothing, and the live programs do not depend on which methods ran.
        for (const Settings::Method method :
             {Settings::Method::Sir, Settings::Method::Isr, Settings::Method::Dir}) {
            auto shade =
                gl::Program::graphics(*c.frame->shaders, "refraction/rectangle.vert.glsl",
                                      "refraction/layers_shade.frag.glsl",
                                      {"LAYER_CAPACITY " + std::to_string(c.settings.layerCapacity),
                                       "LAYER_METHOD " + std::to_string(int(method)),
                                       "LAYER_DISPERSION " + std::to_string(mode)});
            if (!shade)
                return shade.error();
            gpu.layerShadePrograms.insert_or_assign({int(method), mode}, std::move(*shade));
        }
    }
    return &gpu.layerShadePrograms.at(key);
}

std::size_t layerBytesPerPixel(int capacity, bool outlines) {
    // The arrays (head, depth slots, attributes), the depth maps the resolve pass writes, and
    // the nearest layers' map the outline pass reads.
    return 3 * sizeof(std::uint32_t) + depthSlots(capacity) * sizeof(float) +
           std::size_t(capacity) * 2 * sizeof(std::uint32_t) +
           depthSlots(capacity) * sizeof(float) + (outlines ? sizeof(float) : 0);
}

void assignGlassIds(FrameContext& c) {
    const auto& items = c.frame->items;
    c.gpu->glassIds.assign(items.size(), -1);
    c.gpu->glassOptics.clear();
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
        const scene::Material* m =
            item.material >= 0 ? &item.model->materials[std::size_t(item.material)] : nullptr;
        const Optics o = opticsFor(c.settings, m, item.source->overrides);
        const glm::vec3 emissive = m ? m->emissiveFactor * m->emissiveStrength : glm::vec3(0.0f);
        const int solid = solids.emplace(item.key, int(solids.size())).first->second;
        c.gpu->glassOptics.push_back(
            {glm::vec4(o.ior, o.transmission), glm::vec4(o.sigma, o.roughness),
             glm::vec4(glm::vec3(o.baseColor), o.metallic), glm::vec4(emissive, float(solid)),
             glm::vec4(o.specularColor, o.specularWeight),
             glm::vec4(o.clearcoat, o.clearcoatRoughness, o.iridescence, o.iridescenceIor),
             glm::vec4(o.sheenColor, o.sheenRoughness),
             glm::vec4(o.iridescenceThickness, 0.0f, 0.0f, 0.0f)});
        ids.emplace(key, int(c.gpu->glassOptics.size()) - 1);
        c.gpu->glassIds[i] = int(c.gpu->glassOptics.size()) - 1;
    }
    if (full && !c.gpu->warnedGlassIds) {
        core::logWarning("refraction: more than 255 glass materials (character x material) in "
                         "one frame; the layered path draws the rest with the 255th's optics");
        c.gpu->warnedGlassIds = true;
    }
}

fg::TextureHandle addLayerPasses(fg::FrameGraph& graph, const fg::Blackboard& blackboard,
                                 const FrameContext& c, FrameBuffers& buffers) {
    const glm::ivec2 size = c.frame->settings.size;
    const fg::TextureHandle sceneColor = blackboard.get<fg::TextureHandle>(plugin::kSceneColor);
    const fg::TextureHandle sceneDepth = blackboard.get<fg::TextureHandle>(plugin::kSceneDepth);

    struct CaptureData {
        fg::TextureHandle mask;
        fg::BufferHandle layers, rectangle;
    };
    const auto& captured = graph.addPass<CaptureData>(
        "refraction.layers",
        [&](fg::Builder& b, CaptureData& d) {
            b.read(buffers.vertices);
            b.read(buffers.materials);
            if (c.settings.usesNormalDistance())
                b.read(buffers.distances);
            d.mask = b.write(b.create("refraction.layers.mask", {size, gl::Format::Depth32F, 1}));
            d.rectangle = b.write(buffers.rectangle);
            d.layers = b.write(buffers.layers);
        },
        [c](const fg::Resources& r, const CaptureData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            const glm::ivec2 viewport = c.frame->settings.size;
            ensureLayerStorage(gpu.layers, viewport, c.settings.layerCapacity);
            const std::size_t pixels = std::size_t(viewport.x) * std::size_t(viewport.y);
            gpu.layers.heads.fill(0, pixels, 0u);                   // counts
            gpu.layers.heads.fill(pixels * 4, pixels, 0xFFFFFFFFu); // nearest front keys
            gpu.layers.heads.fill(pixels * 8, pixels, 0u);          // farthest back keys
            c.growGlassRectangle();
            // Depth only: the shading pass's mask.
            if (auto bound =
                    gpu.framebuffer.bindTargets("refraction.layers", {}, &r.texture(d.mask));
                !bound)
                return bound;
            gl::clearDepth(1.0f);
            const gl::Program& program = gpu.layersCapture;
            program.use();
            setLayerUniforms(c, program);
            c.drawGlass(program, {.cull = gl::Cull::None, .depthFunc = gl::DepthFunc::Always},
                        [&c, &program](const render::DrawItem& item, std::size_t index) {
                            program.set("uGlassId", c.gpu->glassIds[index]);
                            item.materials->bind(program, *item.model, item.material,
                                                 kMaterialUnit);
                        });
            gl::memoryBarrier(gl::BarrierStorage);
            return {};
        });
    buffers.layers = captured.layers;
    buffers.rectangle = captured.rectangle;

    // The depths the walk's searches read, as maps (one texel fetch per sample).
    struct ResolveData {
        fg::TextureHandle mask, depths0, depths1;
        fg::BufferHandle layers, rectangle;
    };
    const bool twoMaps = c.settings.layerCapacity > 4;
    const gl::TextureDesc depthsDesc{size, gl::Format::RGBA32F, 1};
    const auto& resolved = graph.addPass<ResolveData>(
        "refraction.layer_depths",
        [&](fg::Builder& b, ResolveData& d) {
            d.layers = b.read(buffers.layers);
            d.rectangle = b.read(buffers.rectangle);
            d.mask = b.read(captured.mask);
            d.depths0 = b.write(b.create("refraction.layers.depths0", depthsDesc));
            if (twoMaps)
                d.depths1 = b.write(b.create("refraction.layers.depths1", depthsDesc));
        },
        [c, twoMaps](const fg::Resources& r, const ResolveData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            std::vector<const gl::Texture*> targets{&r.texture(d.depths0)};
            if (twoMaps)
                targets.push_back(&r.texture(d.depths1));
            if (auto bound = gpu.framebuffer.bindTargets("refraction.layer_depths", targets,
                                                         &r.texture(d.mask));
                !bound)
                return bound;
            for (int i = 0; i < int(targets.size()); ++i)
                gl::clearColor(i, glm::vec4(kNoLayer));
            gpu.layersResolve.use();
            setLayerUniforms(c, gpu.layersResolve);
            c.drawMaskedRectangle();
            return {};
        });

    struct ShadeData {
        fg::TextureHandle sceneColor, sceneDepth, mask, depths0, depths1, out, surface;
        fg::BufferHandle layers, rectangle;
    };
    const bool outlines = c.settings.outlineAntialiasing;
    const auto& shaded = graph.addPass<ShadeData>(
        "refraction.shade_layers",
        [&](fg::Builder& b, ShadeData& d) {
            d.layers = b.read(buffers.layers);
            b.read(buffers.materials);
            d.mask = b.read(captured.mask);
            d.depths0 = b.read(resolved.depths0);
            if (resolved.depths1.valid())
                d.depths1 = b.read(resolved.depths1);
            d.rectangle = b.write(buffers.rectangle); // counts the overflowing pixels
            d.sceneColor = b.read(sceneColor);
            d.sceneDepth = b.read(sceneDepth);
            d.out = b.write(b.create("refraction.scene_color", colorDesc(size)));
            if (outlines) // the nearest layer per pixel, for the outline pass
                d.surface =
                    b.write(b.create("refraction.layers.surface", {size, gl::Format::R32UI, 1}));
        },
        [c, outlines](const fg::Resources& r, const ShadeData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            gl::copyTexture(r.texture(d.sceneColor), r.texture(d.out));
            std::vector<const gl::Texture*> targets{&r.texture(d.out)};
            if (outlines)
                targets.push_back(&r.texture(d.surface));
            if (auto bound = gpu.framebuffer.bindTargets("refraction.shade_layers", targets,
                                                         &r.texture(d.mask));
                !bound)
                return bound;
            if (outlines)
                gl::clearColorUint(1, 0u); // no glass
            const gl::Program& program = *c.layerShade;
            c.setWalkUniforms(program);
            program.set("uMarchSteps", c.settings.marchSteps);
            program.set("uInterfaces", c.settings.interfaces);
            setLayerUniforms(c, program);
            gl::bindTexture(kSceneColorUnit, r.texture(d.sceneColor));
            gl::bindTexture(kSceneDepthUnit, r.texture(d.sceneDepth));
            program.set("uSceneColor", kSceneColorUnit);
            program.set("uSceneDepth", kSceneDepthUnit);
            bindLayerDepthMaps(program, r, d.depths0, d.depths1);
            c.drawMaskedRectangle();
            return {};
        });
    buffers.rectangle = shaded.rectangle;
    if (!outlines)
        return shaded.out;

    // The outlines of smooth glass anti-aliased: over the glass rectangle and a pixel around
    // it (the pixels an outline only grazes lie outside the glass).
    struct OutlineData {
        fg::TextureHandle shaded, surface, out;
        fg::BufferHandle rectangle;
    };
    const auto& outlined = graph.addPass<OutlineData>(
        "refraction.layer_outlines",
        [&](fg::Builder& b, OutlineData& d) {
            d.rectangle = b.read(buffers.rectangle);
            d.shaded = b.read(shaded.out);
            d.surface = b.read(shaded.surface);
            d.out = b.write(b.create("refraction.scene_color", colorDesc(size)));
        },
        [c](const fg::Resources& r, const OutlineData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            gl::copyTexture(r.texture(d.shaded), r.texture(d.out));
            if (auto bound = gpu.framebuffer.bindTargets("refraction.layer_outlines",
                                                         {&r.texture(d.out)}, nullptr);
                !bound)
                return bound;
            const gl::Program& program = gpu.layersOutline;
            program.use();
            program.set("uViewportSize", glm::vec2(c.frame->settings.size));
            program.set("uRectangleMargin", 1.0f);
            gl::bindTexture(kSceneColorUnit, r.texture(d.shaded));
            program.set("uColor", kSceneColorUnit);
            gl::bindTexture(kSurfaceUnit, r.texture(d.surface));
            program.set("uSurface", kSurfaceUnit);
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            c.drawRectangle();
            return {};
        });
    return outlined.out;
}

} // namespace refraction
