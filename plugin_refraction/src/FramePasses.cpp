// The refraction passes of one frame.
#include "FramePasses.h"

#include "engine/deform/GpuDeformer.h"
#include "engine/render/Environment.h"
#include "engine/render/MaterialTextures.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>

namespace refraction {
namespace {

constexpr float kNoSurface = -3.0e38f; // surfaces.glsl: the MAX-blended targets' clear value
// The mip level the searches read the surface normals at (DIR §3.1: mip-filtered normals); the
// normal maps need no level above it.
constexpr int kNormalLod = 1;
// Texture units of the shading passes: 0-1 environment, 2-7 the maps (setShading), 8-14 the
// material's textures, then the gathered far target of the single geometry pass.
constexpr std::uint32_t kMaterialUnit = 8,
                        kGatherFarUnit = kMaterialUnit + render::MaterialTextures::kSlotCount;

gl::TextureDesc depthDesc(glm::ivec2 size) {
    return {size, gl::Format::R32F, 1};
}
gl::TextureDesc normalDesc(glm::ivec2 size) {
    return {size, gl::Format::RGBA16F, kNormalLod + 1};
}
gl::TextureDesc zDesc(glm::ivec2 size) {
    return {size, gl::Format::Depth32F, 1};
}
gl::TextureDesc colorDesc(glm::ivec2 size) {
    return {size, gl::Format::RGBA16F, 1};
}

/** What a shading pass reads. */
struct ShadeData {
    SurfaceMaps maps;
    fg::TextureHandle sceneColor, sceneDepth, out, zbuffer;
};

/** Uniforms and maps of glass_shading.glsl common to both shading paths. */
void setShading(const FrameContext& c, const gl::Program& f, const ShadeData& d,
                const fg::Resources& r) {
    c.setWalkUniforms(f);
    f.set("uNormalLod", float(kNormalLod));
    const std::pair<const char*, fg::TextureHandle> samplers[] = {
        {"uBackDepth", d.maps.backDepth},   {"uBackNormal", d.maps.backNormal},
        {"uFrontDepth", d.maps.frontDepth}, {"uFrontNormal", d.maps.frontNormal},
        {"uSceneColor", d.sceneColor},      {"uSceneDepth", d.sceneDepth}};
    int unit = 2;
    for (const auto& [uniform, handle] : samplers) {
        // Maps this method does not read are absent: the scene depth stands in (unread).
        gl::bindTexture(std::uint32_t(unit), r.texture(handle.valid() ? handle : d.sceneDepth));
        f.set(uniform, unit++);
    }
    gl::bindStorage(3, c.gpu->range);
}

} // namespace

FrameBuffers importBuffers(fg::FrameGraph& graph, const fg::Blackboard& blackboard, GpuState& gpu) {
    FrameBuffers buffers;
    buffers.vertices = blackboard.get<fg::BufferHandle>(plugin::kSceneVertices);
    buffers.distances = graph.importBuffer("refraction.distances", &gpu.distances);
    buffers.rectangle = graph.importBuffer("refraction.rectangle", &gpu.rectangle);
    buffers.range = graph.importBuffer("refraction.depth_range", &gpu.range);
    buffers.layers = graph.importBuffer("refraction.layers", &gpu.layers);
    buffers.materials = graph.importBuffer("refraction.glass_materials", &gpu.glassMaterials);
    return buffers;
}

int GpuState::Distance::find(Part part) const {
    const auto at = std::find(parts.begin(), parts.end(), part);
    return at == parts.end() ? -1 : int(at - parts.begin());
}

void dropStaleDistances(GpuState& gpu, std::span<const render::DrawItem> items) {
    std::erase_if(gpu.distances, [&](const auto& entry) {
        return std::none_of(items.begin(), items.end(),
                            [&](const render::DrawItem& item) { return item.key == entry.first; });
    });
}

void FrameContext::setWalkUniforms(const gl::Program& f) const {
    const Settings& s = settings;
    f.use();
    f.set("uMethod", int(s.method)); // 1 sir, 2 isr, 3 dir
    f.set("uSteps", s.searchSteps);
    f.set("uTirPolicy", reflect ? 1 : 0);
    f.set("uBounces", s.tirBounces);
    f.set("uFresnelMode", int(s.fresnel)); // 0 exact, 1 schlick, 2 off
    // Without opaque geometry the walk could only find the background, which is the
    // environment the lookup falls back to: skip it (the same image, cheaper).
    f.set("uNearby", s.nearby && frame->opaqueGeometry ? 1 : 0);
    f.set("uDebug", s.debug);
    f.set("uSharedDispersion", s.dispersionSearch == Settings::DispersionSearch::Shared ? 1 : 0);
    f.set("uViewportSize", glm::vec2(frame->settings.size));
    f.set("uProjection", frame->camera.projection);
    f.set("uInverseProjection", glm::inverse(frame->camera.projection));
    f.set("uNear", frame->camera.znear);
    f.set("uFar", frame->camera.zfar);
    f.set("uNearbyDistance", 0.5f * (frame->camera.zfar - frame->camera.znear));
    const glm::mat4 viewToWorld = glm::inverse(frame->camera.view);
    f.set("uViewToWorld", glm::mat3(viewToWorld));
    f.set("uViewOriginWorld", glm::vec3(viewToWorld[3]));
    frame->environment->bind(f, 0, frame->settings.environmentRotation,
                             frame->settings.environmentIntensity);
}

void FrameContext::setMaterial(const gl::Program& program, std::size_t index) const {
    const render::DrawItem& item = frame->items[index];
    item.materials->bind(program, *item.model, item.material, kMaterialUnit);
    program.set("uGlassId", gpu->glassIds[index]);
    gl::bindStorage(8, gpu->glassMaterials);
}

void addGlassMaterialsPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers) {
    struct Data {
        fg::BufferHandle materials;
    };
    const Data& pass = graph.addPass<Data>(
        "refraction.glass_materials",
        [&](fg::Builder& b, Data& d) { d.materials = b.write(buffers.materials); },
        [c](const fg::Resources&, const Data&, gl::Context&) {
            GpuState& gpu = *c.gpu;
            const std::size_t bytes = gpu.glassOptics.size() * sizeof(GlassMaterialGpu);
            if (gpu.glassMaterials.size() < bytes)
                gpu.glassMaterials = gl::Buffer(bytes);
            gpu.glassMaterials.update(0, bytes, gpu.glassOptics.data());
        });
    buffers.materials = pass.materials;
}

void FrameContext::drawGlass(
    const gl::Program& program, const gl::PipelineState& state,
    const std::function<void(const render::DrawItem&, std::size_t)>& perItem) const {
    program.use();
    program.set("uProjection", frame->camera.projection);
    for (std::size_t index = 0; index < frame->items.size(); ++index) {
        const render::DrawItem& item = frame->items[index];
        if (!isGlass(item))
            continue;
        const glm::mat4 modelView = frame->camera.view * item.world;
        program.set("uModelView", modelView);
        program.set("uNormalMatrix", glm::inverseTranspose(glm::mat3(modelView)));
        gl::bindStorage(0, *item.gpu->deformed);
        gl::bindStorage(1, *item.gpu->uvs);
        // d_N: the character's combined cage values from this part's base, or (subdivision)
        // the part's own drawn values.
        const GpuState::Distance* distance = nullptr;
        int part = -1;
        if (settings.usesNormalDistance())
            if (const auto found = gpu->distances.find(item.key); found != gpu->distances.end()) {
                distance = &found->second;
                part = distance->find({item.instance, item.primitiveIndex});
            }
        const bool hasDistance = distance && part >= 0 && distance->cage;
        const gl::Buffer* values = nullptr;
        int base = 0;
        if (hasDistance) {
            const auto drawn = distance->drawn.find({item.instance, item.primitiveIndex});
            values = drawn != distance->drawn.end() ? &drawn->second : &distance->cage->distances();
            base =
                drawn != distance->drawn.end() ? 0 : int(distance->cage->base(std::size_t(part)));
        }
        program.set("uHasNormalDistance", hasDistance ? 1 : 0);
        program.set("uDistanceBase", base);
        // Without d_N the binding still needs a buffer: the vertices stand in (unread).
        gl::bindStorage(2, values ? *values : *item.gpu->deformed);
        if (perItem)
            perItem(item, index);
        gl::apply(state);
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
    gpu->rectangleGrow.use();
    gpu->rectangleGrow.set("uViewportSize", glm::vec2(frame->settings.size));
    gl::bindStorage(4, gpu->rectangle);
    for (const render::DrawItem& item : frame->items) {
        if (!isGlass(item))
            continue;
        gpu->rectangleGrow.set("uModelViewProjection", frame->camera.viewProjection() * item.world);
        gpu->rectangleGrow.set("uModelView", frame->camera.view * item.world);
        const int count = int(item.primitive->vertexCount());
        gpu->rectangleGrow.set("uVertexCount", count);
        gl::bindStorage(0, item.geometry->cage(item.instance, item.primitiveIndex).vertices);
        gl::dispatch(std::uint32_t((count + 63) / 64));
    }
    gl::memoryBarrier(gl::BarrierStorage);
}

void FrameContext::drawMaskedRectangle() const {
    // The rectangle lies at depth 1: it passes only where the mask holds less.
    gl::apply({.cull = gl::Cull::None, .depthWrite = false, .depthFunc = gl::DepthFunc::Greater});
    drawRectangle();
}

void FrameContext::drawRectangle() const {
    gl::bindStorage(4, gpu->rectangle);
    gpu->emptyVao.bind();
    gl::drawArrays(6);
}

void addNormalDistancePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers) {
    struct Data {
        fg::BufferHandle distances;
    };
    const Data& pass = graph.addPass<Data>(
        "refraction.normal_distance",
        [&](fg::Builder& b, Data& d) {
            b.read(buffers.vertices);
            d.distances = b.write(buffers.distances);
        },
        [c](const fg::Resources&, const Data&, gl::Context&) {
            // The glass items of each character, in frame order: its parts.
            std::map<std::uint64_t, std::vector<const render::DrawItem*>> characters;
            for (const render::DrawItem& item : c.frame->items)
                if (c.isGlass(item))
                    characters[item.key].push_back(&item);
            GpuState& gpu = *c.gpu;
            for (const auto& [key, items] : characters) {
                GpuState::Distance& distance = gpu.distances[key];
                std::vector<GpuState::Distance::Part> parts;
                for (const render::DrawItem* item : items)
                    parts.emplace_back(item->instance, item->primitiveIndex);
                if (!distance.cage || parts != distance.parts) { // new, or other glass parts
                    std::vector<const scene::Primitive*> primitives;
                    for (const render::DrawItem* item : items)
                        primitives.push_back(item->primitive);
                    distance.parts = parts;
                    distance.cage = std::make_unique<NormalDistance>(primitives);
                    distance.drawn.clear();
                }
                for (std::size_t i = 0; i < items.size(); ++i) {
                    const render::DrawItem& item = *items[i];
                    distance.cage->gather(
                        i, item.geometry->cage(item.instance, item.primitiveIndex).vertices,
                        std::uint32_t(item.primitive->vertexCount()), item.world, gpu.cageGather);
                }
                distance.cage->update(gpu.refit, gpu.normalDistance);
                for (std::size_t i = 0; i < items.size(); ++i) {
                    const render::DrawItem& item = *items[i];
                    if (item.geometry->subdivisionLevel() == 0)
                        continue;
                    gl::Buffer& drawn = distance.drawn[parts[i]];
                    if (!drawn)
                        drawn = gl::Buffer(std::size_t(item.gpu->vertexCount) * sizeof(float));
                    item.geometry->refineScalar(item.instance, item.primitiveIndex,
                                                distance.cage->distances(), drawn,
                                                distance.cage->base(i));
                }
            }
        });
    buffers.distances = pass.distances;
}

SurfaceMaps addSeparateSurfacePasses(fg::FrameGraph& graph, const FrameContext& c,
                                     const FrameBuffers& buffers, bool firstBack) {
    struct SurfaceData {
        fg::TextureHandle depth, normal, zbuffer;
    };
    const glm::ivec2 size = c.frame->settings.size;
    // Farthest: GREATER from 0; nearest: LESS from 1.
    auto surfacePass = [&](const char* name, bool backFaces, bool nearest) -> const SurfaceData& {
        return graph.addPass<SurfaceData>(
            name,
            [&](fg::Builder& b, SurfaceData& d) {
                b.read(buffers.vertices);
                if (c.settings.usesNormalDistance())
                    b.read(buffers.distances);
                d.depth = b.write(b.create(std::string(name) + ".depth", depthDesc(size)));
                d.normal = b.write(b.create(std::string(name) + ".normal", normalDesc(size)));
                d.zbuffer = b.write(b.create(std::string(name) + ".zbuffer", zDesc(size)));
            },
            [c, backFaces, nearest, name](const fg::Resources& r, const SurfaceData& d,
                                          gl::Context&) -> core::Status {
                if (auto bound = c.gpu->framebuffer.bindTargets(
                        name, {&r.texture(d.depth), &r.texture(d.normal)}, &r.texture(d.zbuffer));
                    !bound)
                    return bound;
                gl::clearColor(0, glm::vec4(0.0f));
                gl::clearColor(1, glm::vec4(0.0f));
                gl::clearDepth(nearest ? 1.0f : 0.0f);
                c.drawGlass(c.gpu->surface,
                            {.cull = backFaces ? gl::Cull::Front : gl::Cull::Back,
                             .depthFunc = nearest ? gl::DepthFunc::Less : gl::DepthFunc::Greater});
                r.texture(d.normal).generateMipmaps(); // DIR §3.1: mip-filtered normals
                return {};
            });
    };
    SurfaceMaps maps;
    if (c.settings.twoInterfaces()) {
        const SurfaceData& back = surfacePass("refraction.back_faces", true, firstBack);
        maps.backDepth = back.depth;
        maps.backNormal = back.normal;
    }
    if (c.reflect) {
        const SurfaceData& front = surfacePass("refraction.front_depth", false, true);
        maps.frontDepth = front.depth;
        maps.frontNormal = front.normal;
    }
    return maps;
}

SurfaceMaps addGatheredSurfacePasses(fg::FrameGraph& graph, const fg::Blackboard& blackboard,
                                     const FrameContext& c, FrameBuffers& buffers) {
    const glm::ivec2 size = c.frame->settings.size;
    struct GatherData {
        fg::TextureHandle nearTargets, farTargets;
        fg::BufferHandle rectangle;
    };
    const gl::TextureDesc gatherDesc{size, gl::Format::RGBA32F, 1};
    const auto& gathered = graph.addPass<GatherData>(
        "refraction.surfaces",
        [&](fg::Builder& b, GatherData& d) {
            b.read(buffers.vertices);
            if (c.settings.usesNormalDistance())
                b.read(buffers.distances);
            d.rectangle = b.write(buffers.rectangle);
            d.nearTargets = b.write(b.create("refraction.surfaces.near", gatherDesc));
            d.farTargets = b.write(b.create("refraction.surfaces.far", gatherDesc));
        },
        [c](const fg::Resources& r, const GatherData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            const render::FrameInfo& frame = *c.frame;
            c.growGlassRectangle();
            if (auto bound = gpu.framebuffer.bindTargets(
                    "refraction.surfaces", {&r.texture(d.nearTargets), &r.texture(d.farTargets)},
                    nullptr);
                !bound)
                return bound;
            gl::clearColor(0, glm::vec4(kNoSurface));
            gl::clearColor(1, glm::vec4(kNoSurface));
            gpu.surfaces.use();
            gpu.surfaces.set("uKeyNear", frame.camera.znear);
            gpu.surfaces.set("uKeyLogRange", std::log2(frame.camera.zfar / frame.camera.znear));
            c.drawGlass(gpu.surfaces, {.cull = gl::Cull::None,
                                       .depthTest = false,
                                       .depthWrite = false,
                                       .blend = gl::Blend::Max});
            return {};
        });
    buffers.rectangle = gathered.rectangle;

    struct ResolveData {
        fg::TextureHandle nearTargets, farTargets, sceneDepth, backNormal, frontDepth, frontNormal,
            mask;
    };
    const fg::TextureHandle sceneDepth = blackboard.get<fg::TextureHandle>(plugin::kSceneDepth);
    const auto& resolved = graph.addPass<ResolveData>(
        "refraction.resolve",
        [&](fg::Builder& b, ResolveData& d) {
            b.read(buffers.rectangle);
            d.nearTargets = b.read(gathered.nearTargets);
            d.farTargets = b.read(gathered.farTargets);
            d.sceneDepth = b.read(sceneDepth);
            d.backNormal = b.write(b.create("refraction.back.normal", normalDesc(size)));
            if (c.reflect) {
                d.frontDepth = b.write(b.create("refraction.front.depth", depthDesc(size)));
                d.frontNormal = b.write(b.create("refraction.front.normal", normalDesc(size)));
            }
            d.mask = b.write(b.create("refraction.glass_mask", zDesc(size)));
        },
        [c](const fg::Resources& r, const ResolveData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            std::vector<const gl::Texture*> targets{&r.texture(d.backNormal)};
            if (c.reflect)
                targets.insert(targets.end(),
                               {&r.texture(d.frontDepth), &r.texture(d.frontNormal)});
            if (auto bound =
                    gpu.framebuffer.bindTargets("refraction.resolve", targets, &r.texture(d.mask));
                !bound)
                return bound;
            // Outside the glass rectangle: no surface, and the mask rejects.
            for (int i = 0; i < int(targets.size()); ++i)
                gl::clearColor(i, glm::vec4(0.0f));
            gl::clearDepth(1.0f);
            gl::apply({.cull = gl::Cull::None, .depthFunc = gl::DepthFunc::Always});
            gpu.resolve.use();
            const std::pair<const char*, fg::TextureHandle> inputs[] = {
                {"uGatherNear", d.nearTargets},
                {"uGatherFar", d.farTargets},
                {"uSceneDepth", d.sceneDepth}};
            int unit = 0;
            for (const auto& [uniform, handle] : inputs) {
                gl::bindTexture(std::uint32_t(unit), r.texture(handle));
                gpu.resolve.set(uniform, unit++);
            }
            gpu.resolve.set("uNear", c.frame->camera.znear);
            gpu.resolve.set("uFar", c.frame->camera.zfar);
            gpu.resolve.set("uViewportSize", glm::vec2(c.frame->settings.size));
            gl::bindStorage(4, gpu.rectangle);
            gpu.emptyVao.bind();
            gl::drawArrays(6);
            r.texture(d.backNormal).generateMipmaps(); // DIR §3.1: mip-filtered normals
            if (c.reflect) // only TIR bounces toward the front read its normals' mips
                r.texture(d.frontNormal).generateMipmaps();
            return {};
        });
    SurfaceMaps maps;
    maps.backDepth = gathered.nearTargets; // back depth in .r (surfaces.glsl)
    maps.backNormal = resolved.backNormal;
    maps.frontDepth = resolved.frontDepth;
    maps.frontNormal = resolved.frontNormal;
    maps.gatheredFar = gathered.farTargets;
    maps.mask = resolved.mask;
    return maps;
}

void addDepthRangePass(fg::FrameGraph& graph, const FrameContext& c, const SurfaceMaps& maps,
                       FrameBuffers& buffers) {
    struct RangeData {
        fg::TextureHandle back, front;
        fg::BufferHandle rectangle, range;
    };
    const auto& ranged = graph.addPass<RangeData>(
        "refraction.depth_range",
        [&](fg::Builder& b, RangeData& d) {
            // reads the glass rectangle, or (separate passes) sets it to the screen
            d.rectangle = b.write(buffers.rectangle);
            d.range = b.write(buffers.range);
            d.back = b.read(maps.backDepth);
            if (c.reflect)
                d.front = b.read(maps.frontDepth);
        },
        [c](const fg::Resources& r, const RangeData& d, gl::Context&) {
            GpuState& gpu = *c.gpu;
            const glm::ivec2 size = c.frame->settings.size;
            for (std::size_t slot = 0; slot < 2; ++slot) { // min: FLT_MAX bits, max: 0
                gpu.range.fill(8 * slot, 1, 0x7F7FFFFFu);
                gpu.range.fill(8 * slot + 4, 1, 0u);
            }
            if (!c.onePass) { // the separate passes grow no glass rectangle: the screen
                using R = GlassRectangleGpu;
                gpu.rectangle.fill(offsetof(R, pixelMin), 2, 0u);
                gpu.rectangle.fill(offsetof(R, pixelMax), 1, std::uint32_t(size.x - 1));
                gpu.rectangle.fill(offsetof(R, pixelMax) + 4, 1, std::uint32_t(size.y - 1));
            }
            gpu.depthRange.use();
            gl::bindStorage(0, gpu.range);
            gl::bindStorage(4, gpu.rectangle);
            for (int slot = 0; slot < (d.front.valid() ? 2 : 1); ++slot) {
                gl::bindTexture(0, r.texture(slot == 0 ? d.back : d.front));
                gpu.depthRange.set("uDepth", 0);
                gpu.depthRange.set("uSlot", slot);
                gl::dispatch(std::uint32_t((size.x + 63) / 64), std::uint32_t((size.y + 63) / 64));
            }
            gl::memoryBarrier(gl::BarrierStorage);
        });
    buffers.rectangle = ranged.rectangle;
    buffers.range = ranged.range;
}

fg::TextureHandle addShadingPasses(fg::FrameGraph& graph, const fg::Blackboard& blackboard,
                                   const FrameContext& c, const SurfaceMaps& maps,
                                   const FrameBuffers& buffers) {
    const glm::ivec2 size = c.frame->settings.size;
    const fg::TextureHandle sceneColor = blackboard.get<fg::TextureHandle>(plugin::kSceneColor);
    const fg::TextureHandle sceneDepth = blackboard.get<fg::TextureHandle>(plugin::kSceneDepth);
    auto readInputs = [&](fg::Builder& b, ShadeData& d) {
        if (!c.onePass) // the front faces are drawn again; one pass shades the maps alone
            b.read(buffers.vertices);
        b.read(buffers.rectangle);
        b.read(buffers.materials);
        if (c.settings.twoInterfaces())
            b.read(buffers.range);
        if (c.settings.usesNormalDistance())
            b.read(buffers.distances);
        for (auto [from, to] :
             {std::pair{maps.backDepth, &d.maps.backDepth},
              std::pair{maps.backNormal, &d.maps.backNormal},
              std::pair{maps.frontDepth, &d.maps.frontDepth},
              std::pair{maps.frontNormal, &d.maps.frontNormal},
              std::pair{maps.gatheredFar, &d.maps.gatheredFar}, std::pair{maps.mask, &d.maps.mask}})
            if (from.valid())
                *to = b.read(from);
        d.sceneColor = b.read(sceneColor);
        d.sceneDepth = b.read(sceneDepth);
    };

    if (c.onePass) {
        // The scene colour copied, then one pass over the glass rectangle shades the glass
        // pixels (the mask's early depth test skips the others).
        const auto& shaded = graph.addPass<ShadeData>(
            "refraction.shade",
            [&](fg::Builder& b, ShadeData& d) {
                readInputs(b, d);
                d.out = b.write(b.create("refraction.scene_color", colorDesc(size)));
            },
            [c](const fg::Resources& r, const ShadeData& d, gl::Context&) -> core::Status {
                GpuState& gpu = *c.gpu;
                gl::copyTexture(r.texture(d.sceneColor), r.texture(d.out));
                if (auto bound = gpu.framebuffer.bindTargets(
                        "refraction.shade", {&r.texture(d.out)}, &r.texture(d.maps.mask));
                    !bound)
                    return bound;
                setShading(c, gpu.deferred, d, r);
                c.setMaterial(gpu.deferred, c.glassIndex);
                gl::bindTexture(kGatherFarUnit, r.texture(d.maps.gatheredFar));
                gpu.deferred.set("uGatherFar", int(kGatherFarUnit));
                c.drawMaskedRectangle();
                return {};
            });
        return shaded.out;
    }

    // Front faces: refract, find the exit, shade; then the glass over the scene colour.
    const auto& shaded = graph.addPass<ShadeData>(
        "refraction.front_faces",
        [&](fg::Builder& b, ShadeData& d) {
            readInputs(b, d);
            d.out = b.write(b.create("refraction.glass", colorDesc(size)));
            d.zbuffer = b.write(b.create("refraction.glass_zbuffer", zDesc(size)));
        },
        [c](const fg::Resources& r, const ShadeData& d, gl::Context&) -> core::Status {
            if (auto bound = c.gpu->framebuffer.bindTargets(
                    "refraction.front_faces", {&r.texture(d.out)}, &r.texture(d.zbuffer));
                !bound)
                return bound;
            gl::clearColor(0, glm::vec4(0.0f));
            gl::clearDepth(1.0f);
            setShading(c, c.gpu->front, d, r);
            c.drawGlass(c.gpu->front, {.cull = gl::Cull::Back, .depthFunc = gl::DepthFunc::Less},
                        [&c](const render::DrawItem&, std::size_t index) {
                            c.setMaterial(c.gpu->front, index);
                        });
            return {};
        });
    struct CompositeData {
        fg::TextureHandle scene, glass, out;
    };
    const auto& composite = graph.addPass<CompositeData>(
        "refraction.composite",
        [&](fg::Builder& b, CompositeData& d) {
            d.scene = b.read(sceneColor);
            d.glass = b.read(shaded.out);
            d.out = b.write(b.create("refraction.scene_color", colorDesc(size)));
        },
        [c](const fg::Resources& r, const CompositeData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            if (auto bound = gpu.framebuffer.bindTargets("refraction.composite",
                                                         {&r.texture(d.out)}, nullptr);
                !bound)
                return bound;
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            gpu.composite.use();
            gl::bindTexture(0, r.texture(d.scene));
            gl::bindTexture(1, r.texture(d.glass));
            gpu.composite.set("uScene", 0);
            gpu.composite.set("uGlass", 1);
            gpu.emptyVao.bind();
            gl::drawArrays(3);
            return {};
        });
    return composite.out;
}

} // namespace refraction
