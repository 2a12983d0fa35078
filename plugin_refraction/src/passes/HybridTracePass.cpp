// `refraction.hybrid_trace`: the pixels the hybrid's walk handed over (the layers could not hold
// their path), traced, every sample (ListedSamples.cpp); where the frame accumulates, their
// motion over the walk's, and the first sample lists those whose history will be rejected, as
// the walk lists its own.
#include "Passes.h"

namespace refraction {

Walked addHybridTracePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                          const SceneInputs& scene, const Capture& capture, const Walked& walked) {
    const auto& traced = graph.addPass<TraceData>(
        "refraction.hybrid_trace",
        [&](fg::Builder& b, TraceData& d) {
            declareListedSamples(b, d, c, buffers, scene, capture, walked,
                                 ListedPixels::HandedOver);
        },
        [c](const fg::Resources& r, const TraceData& d, gl::Context&) {
            const int samples = c.traceSamples();
            return sampleList(r, d, c, ListedPixels::HandedOver, 0, samples, samples);
        });
    buffers.counters = traced.counters;
    return {traced.color, walked.surface, traced.motion};
}

} // namespace refraction
