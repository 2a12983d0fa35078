// `refraction.layer_overflow`: after the capture, the pixels it listed as overflowing (more
// than K glass fragments) each have their K kept layers bid for the pixel's fallback from their
// slots, as the fragments past K bid while drawn (layer_overflow.comp.glsl). One indirect
// dispatch over the list: a frame without overflow dispatches no work group.
#include "Passes.h"

namespace refraction {

void addLayerOverflowPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers) {
    struct OverflowData {
        LayerBuffers layers;
    };
    const auto& bid = graph.addPass<OverflowData>(
        "refraction.layer_overflow",
        [&](fg::Builder& b, OverflowData& d) { d.layers = writeLayers(b, buffers.layers); },
        [c, defines = layerDefines(c)](const fg::Resources& r, const OverflowData& d,
                                       gl::Context&) -> core::Status {
            auto program = c.compute("refraction/passes/layer_overflow.comp.glsl", defines);
            if (!program)
                return program.error();
            (*program)->use();
            c.setLayerUniforms(**program, r, d.layers);
            // the list's work groups, after its count (layers.glsl overflowIndex)
            gl::dispatchIndirect(r.buffer(d.layers.heads),
                                 overflowListOffset(d.layers.shape) + sizeof(std::uint32_t));
            // the arrays for the passes that read them; the heads for the next frame's clear
            gl::memoryBarrier(gl::BarrierStorage | gl::BarrierBufferUpdate);
            return {};
        });
    buffers.layers = bid.layers;
}

} // namespace refraction
