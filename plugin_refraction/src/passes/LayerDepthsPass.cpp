// `refraction.layer_depths`: the layers' depths resolved, over the glass pixels, into the one or
// two RGBA32F maps the walk's searches read (one texel fetch per sample; the overflow pair in
// place, negated: layer_depths.frag.glsl), after an overflowing pixel's kept layers bid for its
// fallback (writes layers).
#include "Passes.h"

#include <vector>

namespace refraction {

Capture addLayerDepthsPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                           fg::TextureHandle mask) {
    const glm::ivec2 size = c.frame->settings.size;
    // The depths the walk's searches read, as maps (one texel fetch per sample).
    struct ResolveData {
        fg::TextureHandle mask, depths0, depths1;
        fg::BufferHandle layers;
    };
    const bool twoMaps = c.settings.layerCapacity > 4;
    const gl::TextureDesc depthsDesc{size, gl::Format::RGBA32F, 1};
    const auto& resolved = graph.addPass<ResolveData>(
        "refraction.layer_depths",
        [&](fg::Builder& b, ResolveData& d) {
            d.layers = b.write(buffers.layers);
            b.read(buffers.extent);
            d.mask = b.read(mask);
            d.depths0 = b.write(b.create("refraction.layer_depths.depths0", depthsDesc));
            if (twoMaps)
                d.depths1 = b.write(b.create("refraction.layer_depths.depths1", depthsDesc));
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
                gl::clearColor(i, glm::vec4(kNoDepth));
            c.capture.resolve->use();
            c.setLayerUniforms(*c.capture.resolve);
            c.drawMaskedRectangle();
            gl::memoryBarrier(gl::BarrierStorage); // the fallback, for the passes that read it
            return {};
        });
    buffers.layers = resolved.layers;

    Capture capture;
    capture.mask = mask;
    capture.depths0 = resolved.depths0;
    capture.depths1 = resolved.depths1;
    return capture;
}

} // namespace refraction
