// `refraction.surfaces`: the pair capture in one geometry pass, every glass item at once over
// MAX-blended targets that keep each pixel's nearest front and farthest back with their normals
// and d_N keys (surfaces.frag.glsl), growing the glass rectangle first.
#include "Passes.h"

#include <cmath>

namespace refraction {

PairTargets addGatherPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers) {
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
    PairTargets pair;
    pair.nearTargets = gathered.nearTargets;
    pair.farTargets = gathered.farTargets;
    return pair;
}

} // namespace refraction
