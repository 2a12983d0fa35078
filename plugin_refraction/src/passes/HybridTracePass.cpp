// `refraction.hybrid_trace`: the pixels the hybrid's walk handed over (the layers could not hold
// their path) traced as the trace traces them, over the walk's colour (hybrid_trace.comp.glsl),
// a dispatch each sample of as many work groups as the walk counted; where the frame
// accumulates, their motion over the walk's.
#include "Passes.h"

#include <cstdint>

namespace refraction {

Walked addHybridTracePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                          const SceneInputs& scene, const Capture& capture, const Walked& walked) {
    struct TraceData {
        WalkInputs in;
        fg::TextureHandle sceneMotion, color, motion;
        fg::BufferHandle counters;
    };
    const auto& traced = graph.addPass<TraceData>(
        "refraction.hybrid_trace",
        [&](fg::Builder& b, TraceData& d) {
            d.in = readWalkInputs(b, c, buffers, scene, capture);
            b.read(buffers.handedOver);
            d.counters = b.write(buffers.counters);
            d.color = b.write(walked.color);
            if (walked.motion.valid()) {
                d.sceneMotion = b.read(scene.motion);
                d.motion = b.write(walked.motion);
            }
        },
        [c](const fg::Resources& r, const TraceData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            if (auto bound = bindWalkInputs(r, c, d.in); !bound)
                return bound;
            gl::bindStorage(slot::kHandedOver, gpu.handedOver);
            const gl::Program& program = *c.hybridTrace;
            const int samples = c.traceSamples();
            c.setWalkUniforms(program);
            c.setLayerUniforms(program);
            program.set("uTraceWeight", 1.0f / float(samples));
            gl::bindImage(gl::slot::kOutputImage, r.texture(d.color), 0, true);
            if (d.motion.valid()) {
                gl::bindTexture(gl::slot::kMotion, r.texture(d.sceneMotion));
                gl::bindImage(gl::slot::kMotionImage, r.texture(d.motion), 0, true);
            }
            for (int s = 0; s < samples; ++s) {
                program.set("uTraceSample", s);
                gl::dispatchIndirect(gpu.handedOver, sizeof(std::uint32_t));
                gl::memoryBarrier(gl::BarrierImage);
            }
            gl::memoryBarrier(gl::BarrierTexture | gl::BarrierFramebuffer);
            return {};
        });
    buffers.counters = traced.counters;
    return {traced.color, walked.surface, traced.motion};
}

} // namespace refraction
