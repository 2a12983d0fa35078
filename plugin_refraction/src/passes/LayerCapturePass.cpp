// `refraction.layer_capture`: the layered capture. Every glass item of every character in one
// geometry pass, each fragment into its pixel's layer arrays (at most K; a fragment past K bids
// for the pixel's overflow fallback, the nearest front and farthest back, and the first lists
// the pixel for refraction.layer_overflow); the depth attachment becomes the glass pixels' mask.
#include "Passes.h"

namespace refraction {

fg::TextureHandle addLayerCapturePass(fg::FrameGraph& graph, const FrameContext& c,
                                      FrameBuffers& buffers) {
    const glm::ivec2 size = c.frame->settings.size;
    struct CaptureData {
        fg::TextureHandle mask;
        LayerBuffers layers;
        GlassDrawn glass;
    };
    // With textured glass each layer's surface (and the fallback's bid in the heads); where the
    // frame accumulates, each layer's motion.
    const LayerShape shape{size, c.settings.layerCapacity,
                           c.texturedGlass ? c.settings.layerCapacity : 0,
                           c.frame->temporal.enabled};
    c.gpu->layers = shape;
    const auto& captured = graph.addPass<CaptureData>(
        "refraction.layer_capture",
        [&](fg::Builder& b, CaptureData& d) {
            d.glass = readGlassDrawn(b, c, buffers);
            d.mask = b.write(b.create("refraction.layer_capture.mask", zDesc(size)));
            d.layers = createLayers(b, shape);
        },
        [c, defines = layerDefines(c)](const fg::Resources& r, const CaptureData& d,
                                       gl::Context&) -> core::Status {
            auto program = c.graphics("refraction/passes/glass.vert.glsl",
                                      "refraction/passes/layer_capture.frag.glsl", defines);
            if (!program)
                return program.error();
            GpuState& gpu = *c.gpu;
            // The counts, then the fallback's nearest front (bid down from the most) and
            // farthest back (bid up from 0) words, a plane of pixels each, then the overflow
            // list's count and work groups (layers.glsl).
            const LayerShape& made = d.layers.shape;
            const std::size_t pixels = made.pixels();
            const std::size_t side = (layerHeadPlanes(made.surfaceSlots) - 1) / 2 * pixels;
            const std::size_t word = sizeof(std::uint32_t), list = overflowListOffset(made);
            gl::Buffer& heads = r.buffer(d.layers.heads);
            heads.fill(0, pixels, 0u);
            heads.fill(pixels * word, side, 0xFFFFFFFFu);
            heads.fill((pixels + side) * word, side, 0u);
            heads.fill(list, 2, 0u);
            heads.fill(list + 2 * word, 2, 1u);
            // Depth only: the shading pass's mask.
            if (auto bound =
                    gpu.framebuffer.bindTargets("refraction.layer_capture", {}, &r.texture(d.mask));
                !bound)
                return bound;
            gl::clearDepth(1.0f);
            (*program)->use();
            c.setLayerUniforms(**program, r, d.layers);
            c.drawGlassMaterials(**program,
                                 {.cull = gl::Cull::None, .depthFunc = gl::DepthFunc::Always}, r,
                                 d.glass);
            // the arrays and the overflow list for layer_overflow's dispatch
            gl::memoryBarrier(gl::BarrierStorage | gl::BarrierCommand);
            return {};
        });
    buffers.layers = captured.layers;
    return captured.mask;
}

} // namespace refraction
