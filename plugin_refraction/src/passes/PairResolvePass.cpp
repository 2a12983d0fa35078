// `refraction.pair_resolve`: the pair capture resolved over the glass rectangle into layers 0
// and 1 of the layer arrays (K = 2; with textured glass their surfaces too) and the first depth
// map, the depth ranges of its back and front, and the walk's mask; from one gathered pass also
// the mip-filtered normal maps the papers' search reads (pair_resolve.frag.glsl).
#include "Passes.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace refraction {

namespace {

struct ResolveData {
    PairTargets pair;
    fg::TextureHandle sceneDepth, depths0, normals[2], mask;
    LayerBuffers layers;
    fg::BufferHandle extent, pairRanges, materials;
};

/** The resolve's variant: of the one gathered pass, or of the two passes (with the glass's
 *  model, which their surfaces carry). */
core::Result<const gl::Program*> resolveProgram(const FrameContext& c, bool gathered) {
    const std::vector<std::string> pair = {"LAYER_CAPACITY 2", define("PAIR_GATHERED", gathered)};
    return c.graphics(
        "refraction/passes/rectangle.vert.glsl", "refraction/passes/pair_resolve.frag.glsl",
        gathered ? pair
                 : concat(c.glassModel,
                          concat(pair, {define("WRITE_MOTION", c.frame->temporal.enabled)})));
}

core::Status resolvePair(const fg::Resources& r, const ResolveData& d, const FrameContext& c) {
    GpuState& gpu = *c.gpu;
    const bool gathered = d.pair.nearTargets.valid();
    auto resolve = resolveProgram(c, gathered);
    if (!resolve)
        return resolve.error();
    const bool surfaces = d.pair.frontSurface.valid();
    std::vector<const gl::Texture*> targets{&r.texture(d.depths0)};
    if (gathered)
        targets.insert(targets.end(), {&r.texture(d.normals[0]), &r.texture(d.normals[1])});
    if (auto bound =
            gpu.framebuffer.bindTargets("refraction.pair_resolve", targets, &r.texture(d.mask));
        !bound)
        return bound;
    // Outside the glass rectangle: no surface, and the mask rejects.
    gl::clearColor(0, glm::vec4(kNoDepth));
    for (int i = 1; i < int(targets.size()); ++i)
        gl::clearColor(i, glm::vec4(0.0f));
    gl::clearDepth(1.0f);
    // The depth ranges empty: the back's [FLT_MAX, 0], the front's nearest FLT_MAX.
    constexpr std::uint32_t kFloatMax = 0x7F7FFFFFu;
    gl::Buffer& ranges = r.buffer(d.pairRanges);
    ranges.fill(offsetof(PairRangesGpu, backRange), 1, kFloatMax);
    ranges.fill(offsetof(PairRangesGpu, backRange) + 4, 1, 0u);
    ranges.fill(offsetof(PairRangesGpu, frontMin), 1, kFloatMax);
    gl::bindStorage(slot::kPairRanges, ranges);
    gl::apply({.cull = gl::Cull::None, .depthFunc = gl::DepthFunc::Always});
    const gl::Program& program = **resolve;
    program.use();
    c.setLayerUniforms(program, r, d.layers);
    gl::bindStorage(slot::kGlassMaterials, r.buffer(d.materials));
    // The pair's maps in pair_resolve.frag.glsl's order (one pass's two, or two passes' four).
    const fg::TextureHandle maps[] = {d.pair.nearTargets, d.pair.farTargets, d.pair.frontDepth,
                                      d.pair.frontNormal, d.pair.backDepth,  d.pair.backNormal};
    std::uint32_t element = 0;
    for (const fg::TextureHandle handle : maps)
        if (handle.valid())
            gl::bindTexture(slot::kPairMaps, r.texture(handle), element++);
    if (surfaces) {
        gl::bindTexture(slot::kPairSurfaces, r.texture(d.pair.frontSurface), 0);
        gl::bindTexture(slot::kPairSurfaces, r.texture(d.pair.backSurface), 1);
    }
    gl::bindTexture(slot::kSceneDepth, r.texture(d.sceneDepth));
    program.set("uGlassId", c.firstGlassId);
    program.set("uNear", c.frame->camera.znear);
    program.set("uFar", c.frame->camera.zfar);
    c.drawRectangle(r.buffer(d.extent));
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierBufferUpdate); // and the next clear
    if (gathered) {
        r.texture(d.normals[1]).generateMipmaps(); // DIR §3.1: mip-filtered normals
        if (c.reflect) // only TIR bounces toward the front read its normals' mips
            r.texture(d.normals[0]).generateMipmaps();
    }
    return {};
}

} // namespace

Capture addPairResolvePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                           const SceneInputs& scene, const PairTargets& pair) {
    const glm::ivec2 size = c.frame->settings.size;
    const bool gathered = pair.nearTargets.valid();
    // Layers 0 and 1 (K = 2), with textured glass their surfaces, where the frame accumulates
    // the front's motion.
    const LayerShape shape{size, 2, pair.frontSurface.valid() ? 2 : 0, c.frame->temporal.enabled};
    c.gpu->layers = shape;
    const auto& resolved = graph.addPass<ResolveData>(
        "refraction.pair_resolve",
        [&](fg::Builder& b, ResolveData& d) {
            d.extent = b.read(buffers.extent);
            d.materials = b.read(buffers.materials);
            d.pairRanges = b.write(b.create("refraction.pair_ranges", {sizeof(PairRangesGpu)}));
            d.layers = createLayers(b, shape);
            for (auto [from, to] : {std::pair{pair.nearTargets, &d.pair.nearTargets},
                                    std::pair{pair.farTargets, &d.pair.farTargets},
                                    std::pair{pair.frontDepth, &d.pair.frontDepth},
                                    std::pair{pair.frontNormal, &d.pair.frontNormal},
                                    std::pair{pair.backDepth, &d.pair.backDepth},
                                    std::pair{pair.backNormal, &d.pair.backNormal},
                                    std::pair{pair.frontSurface, &d.pair.frontSurface},
                                    std::pair{pair.backSurface, &d.pair.backSurface}})
                if (from.valid())
                    *to = b.read(from);
            d.sceneDepth = b.read(scene.depth);
            d.depths0 = b.write(
                b.create("refraction.pair_resolve.depths0", {size, gl::Format::RGBA32F, 1}));
            if (gathered)
                for (int i = 0; i < 2; ++i)
                    d.normals[i] = b.write(b.create(i == 0 ? "refraction.pair_resolve.front_normal"
                                                           : "refraction.pair_resolve.back_normal",
                                                    normalDesc(size)));
            d.mask = b.write(b.create("refraction.pair_resolve.mask", zDesc(size)));
        },
        [c](const fg::Resources& r, const ResolveData& d, gl::Context&) {
            return resolvePair(r, d, c);
        });
    buffers.pairRanges = resolved.pairRanges;
    buffers.layers = resolved.layers;
    Capture capture;
    capture.mask = resolved.mask;
    capture.depths0 = resolved.depths0;
    capture.normals[0] = gathered ? resolved.normals[0] : pair.frontNormal;
    capture.normals[1] = gathered ? resolved.normals[1] : pair.backNormal;
    return capture;
}

} // namespace refraction
