// Samples of a list of pixels (listed_samples.comp.glsl: a dispatch each sample of as many work
// groups as the list holds), over the walk's colour, traced (the walk compiled as the trace's
// variant); the trace's and the hybrid's:
//   `refraction.hybrid_trace`: the pixels the hybrid's walk handed over (the layers could not
//   hold their path), every sample; where the frame accumulates, their motion over the walk's,
//   and the first sample lists those whose history will be rejected, as the walk lists its own;
//   `refraction.fresh_samples`: while a frame accumulates and anything moves, the later samples
//   of the pixels listed so (FrameContext::freshSamples), added to the first.
#include "Passes.h"

#include <cstddef>
#include <cstdint>

namespace refraction {

namespace {

struct TraceData {
    WalkInputs in;
    fg::TextureHandle sceneMotion, historyColor, historyMotion, color, motion;
    fg::BufferHandle counters;
};

enum class List : int { HandedOver, Fresh };

/** Declares the pass's reads and writes over the walk's outputs. */
void declare(fg::Builder& b, TraceData& d, const FrameContext& c, FrameBuffers& buffers,
             const SceneInputs& scene, const Capture& capture, const Walked& walked, List list) {
    d.in = readWalkInputs(b, c, buffers, scene, capture);
    b.read(buffers.handedOver); // the traced samples' program reads the hybrid's list
    d.counters = b.write(buffers.counters);
    d.color = b.write(walked.color);
    if (list == List::HandedOver && walked.motion.valid()) {
        d.sceneMotion = b.read(scene.motion);
        d.motion = b.write(walked.motion);
        if (c.freshSamples() > 1) {
            d.historyColor = b.read(scene.historyColor);
            d.historyMotion = b.read(scene.historyMotion);
        }
    }
}

/** Samples [first, last) of the list's pixels, each weighing 1 / `samples`. */
core::Status sampleList(const fg::Resources& r, const TraceData& d, const FrameContext& c,
                        List list, int first, int last, int samples) {
    GpuState& gpu = *c.gpu;
    if (auto bound = bindWalkInputs(r, c, d.in); !bound)
        return bound;
    gl::bindStorage(slot::kHandedOver, gpu.handedOver);
    const gl::Program& program = *c.listedSamples;
    c.setWalkUniforms(program);
    c.setLayerUniforms(program);
    program.set("uFreshList", list == List::Fresh ? 1 : 0);
    program.set("uTraceWeight", 1.0f / float(samples));
    gl::bindImage(gl::slot::kOutputImage, r.texture(d.color), 0, true);
    if (d.motion.valid()) {
        gl::bindTexture(gl::slot::kMotion, r.texture(d.sceneMotion));
        gl::bindImage(gl::slot::kMotionImage, r.texture(d.motion), 0, true);
    }
    if (d.historyMotion.valid())
        bindHistory(r, d.historyColor, d.historyMotion);
    for (int s = first; s < last; ++s) {
        program.set("uTraceSample", s);
        if (list == List::Fresh)
            gl::dispatchIndirect(gpu.counters, offsetof(WalkCountersGpu, freshGroups));
        else
            gl::dispatchIndirect(gpu.handedOver, sizeof(std::uint32_t));
        gl::memoryBarrier(gl::BarrierImage | gl::BarrierStorage | gl::BarrierCommand);
    }
    gl::memoryBarrier(gl::BarrierTexture | gl::BarrierFramebuffer | gl::BarrierBufferUpdate);
    return {};
}

} // namespace

Walked addHybridTracePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                          const SceneInputs& scene, const Capture& capture, const Walked& walked) {
    const auto& traced = graph.addPass<TraceData>(
        "refraction.hybrid_trace",
        [&](fg::Builder& b, TraceData& d) {
            declare(b, d, c, buffers, scene, capture, walked, List::HandedOver);
        },
        [c](const fg::Resources& r, const TraceData& d, gl::Context&) {
            const int samples = c.traceSamples();
            return sampleList(r, d, c, List::HandedOver, 0, samples, samples);
        });
    buffers.counters = traced.counters;
    return {traced.color, walked.surface, traced.motion};
}

Walked addFreshSamplesPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                           const SceneInputs& scene, const Capture& capture, const Walked& walked) {
    const auto& traced = graph.addPass<TraceData>(
        "refraction.fresh_samples",
        [&](fg::Builder& b, TraceData& d) {
            declare(b, d, c, buffers, scene, capture, walked, List::Fresh);
        },
        [c](const fg::Resources& r, const TraceData& d, gl::Context&) {
            const int samples = c.freshSamples();
            return sampleList(r, d, c, List::Fresh, 1, samples, samples);
        });
    buffers.counters = traced.counters;
    return {traced.color, walked.surface, walked.motion};
}

} // namespace refraction
