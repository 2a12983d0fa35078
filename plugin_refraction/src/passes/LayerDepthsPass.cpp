// `refraction.layer_depths`: the layers' depths resolved, over the glass pixels, into the one or
// two RGBA32F maps the walk's searches read (one texel fetch per sample; the overflow pair in
// place, negated: layer_depths.frag.glsl).
#include "Passes.h"

#include <vector>

namespace refraction {

Capture addLayerDepthsPass(fg::FrameGraph& graph, const FrameContext& c,
                           const FrameBuffers& buffers, fg::TextureHandle mask) {
    const glm::ivec2 size = c.frame->settings.size;
    // The depths the walk's searches read, as maps (one texel fetch per sample).
    struct ResolveData {
        fg::TextureHandle mask, depths0, depths1;
        LayerBuffers layers;
        fg::BufferHandle extent;
    };
    const bool twoMaps = c.settings.layerCapacity > 4;
    const gl::TextureDesc depthsDesc{size, gl::Format::RGBA32F, 1};
    const auto& resolved = graph.addPass<ResolveData>(
        "refraction.layer_depths",
        [&](fg::Builder& b, ResolveData& d) {
            d.layers = readLayers(b, buffers.layers);
            d.extent = b.read(buffers.extent);
            d.mask = b.read(mask);
            d.depths0 = b.write(b.create("refraction.layer_depths.depths0", depthsDesc));
            if (twoMaps)
                d.depths1 = b.write(b.create("refraction.layer_depths.depths1", depthsDesc));
        },
        [c, twoMaps, defines = layerDefines(c)](const fg::Resources& r, const ResolveData& d,
                                                gl::Context&) -> core::Status {
            auto program = c.graphics("refraction/passes/rectangle.vert.glsl",
                                      "refraction/passes/layer_depths.frag.glsl", defines);
            if (!program)
                return program.error();
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
            (*program)->use();
            c.setLayerUniforms(**program, r, d.layers);
            c.drawMaskedRectangle(r.buffer(d.extent));
            return {};
        });

    Capture capture;
    capture.mask = mask;
    capture.depths0 = resolved.depths0;
    capture.depths1 = resolved.depths1;
    return capture;
}

} // namespace refraction
