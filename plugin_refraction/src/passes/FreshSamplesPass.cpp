// `refraction.fresh_samples`: while a frame accumulates and anything moves, the later samples
// of the pixels listed so (FrameContext::freshSamples), traced (ListedSamples.cpp) and added to
// the first.
#include "Passes.h"

namespace refraction {

Walked addFreshSamplesPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                           const SceneInputs& scene, const Capture& capture, const Walked& walked) {
    const auto& traced = graph.addPass<TraceData>(
        "refraction.fresh_samples",
        [&](fg::Builder& b, TraceData& d) {
            declareListedSamples(b, d, c, buffers, scene, capture, walked, ListedPixels::Fresh);
        },
        [c](const fg::Resources& r, const TraceData& d, gl::Context&) {
            const int samples = c.freshSamples();
            return sampleList(r, d, c, ListedPixels::Fresh, 1, samples, samples);
        });
    buffers.counters = traced.counters;
    return {traced.color, walked.surface, walked.motion};
}

} // namespace refraction
