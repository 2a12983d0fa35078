// `refraction.pair_gather`: the pair capture in one geometry pass, every glass item at once over
// MAX-blended targets that keep each pixel's nearest front and farthest back with their normals
// and d_N keys (pair_gather.frag.glsl).
#include "Passes.h"

#include <cmath>

namespace refraction {

PairTargets addPairGatherPass(fg::FrameGraph& graph, const FrameContext& c,
                              const FrameBuffers& buffers) {
    const glm::ivec2 size = c.frame->settings.size;
    struct GatherData {
        fg::TextureHandle nearTargets, farTargets;
        GlassDrawn glass;
    };
    const gl::TextureDesc gatherDesc{size, gl::Format::RGBA32F, 1};
    const auto& gathered = graph.addPass<GatherData>(
        "refraction.pair_gather",
        [&](fg::Builder& b, GatherData& d) {
            d.glass = readGlassDrawn(b, c, buffers);
            d.nearTargets = b.write(b.create("refraction.pair_gather.near", gatherDesc));
            d.farTargets = b.write(b.create("refraction.pair_gather.far", gatherDesc));
        },
        [c](const fg::Resources& r, const GatherData& d, gl::Context&) -> core::Status {
            auto gather = c.graphics("refraction/passes/glass.vert.glsl",
                                     "refraction/passes/pair_gather.frag.glsl");
            if (!gather)
                return gather.error();
            const gl::Program& program = **gather;
            GpuState& gpu = *c.gpu;
            const render::FrameInfo& frame = *c.frame;
            if (auto bound = gpu.framebuffer.bindTargets(
                    "refraction.pair_gather", {&r.texture(d.nearTargets), &r.texture(d.farTargets)},
                    nullptr);
                !bound)
                return bound;
            gl::clearColor(0, glm::vec4(kNoSurface));
            gl::clearColor(1, glm::vec4(kNoSurface));
            program.use();
            program.set("uKeyNear", frame.camera.znear);
            program.set("uKeyLogRange", std::log2(frame.camera.zfar / frame.camera.znear));
            c.drawGlass(program,
                        {.cull = gl::Cull::None,
                         .depthTest = false,
                         .depthWrite = false,
                         .blend = gl::Blend::Max},
                        r, d.glass);
            return {};
        });
    PairTargets pair;
    pair.nearTargets = gathered.nearTargets;
    pair.farTargets = gathered.farTargets;
    return pair;
}

} // namespace refraction
