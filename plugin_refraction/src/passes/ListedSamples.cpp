// Samples of a list of pixels (listed_samples.glsl: a dispatch each sample of as many work
// groups as the list holds), over the walk's colour, traced (the walk compiled as the trace's
// variant): what the trace's and the hybrid's two listed passes share (HybridTracePass.cpp,
// FreshSamplesPass.cpp).
#include "Passes.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace refraction {

void declareListedSamples(fg::Builder& b, TraceData& d, const FrameContext& c,
                          FrameBuffers& buffers, const SceneInputs& scene, const Capture& capture,
                          const Walked& walked, ListedPixels list) {
    d.in = readWalkInputs(b, c, buffers, scene, capture);
    d.handedOver = b.read(buffers.handedOver); // the traced samples' program reads the list
    d.counters = b.write(buffers.counters);
    d.color = b.write(walked.color);
    if (list == ListedPixels::HandedOver && walked.motion.valid()) {
        d.sceneMotion = b.read(scene.motion);
        d.motion = b.write(walked.motion);
        if (c.freshSamples() > 1) {
            d.historyColor = b.read(scene.historyColor);
            d.historyMotion = b.read(scene.historyMotion);
        }
    }
}

namespace {

/** The program of `list`'s pass, storing the format of the walk's target: the trace's variant
 *  of the walk, over the hybrid's list too (its handed-over pixels are traced). */
core::Result<const gl::Program*> listedProgram(const FrameContext& c, ListedPixels list) {
    std::vector<std::string> defines = walkDefines(c, Settings::Method::Trace);
    *std::find(defines.begin(), defines.end(), "HYBRID_LIST 0") = "HYBRID_LIST 1";
    defines.push_back(std::string("SHADED_FORMAT ") +
                      (c.settings.addsSamples() ? "rgba32f" : "rgba16f"));
    return c.compute(list == ListedPixels::Fresh ? "refraction/passes/fresh_samples.comp.glsl"
                                                 : "refraction/passes/hybrid_trace.comp.glsl",
                     defines);
}

} // namespace

core::Status sampleList(const fg::Resources& r, const TraceData& d, const FrameContext& c,
                        ListedPixels list, int first, int last, int samples) {
    auto listed = listedProgram(c, list);
    if (!listed)
        return listed.error();
    const gl::Program& program = **listed;
    if (auto bound = bindWalkInputs(r, c, d.in, d.counters); !bound)
        return bound;
    gl::Buffer& handedOver = r.buffer(d.handedOver);
    gl::bindStorage(slot::kHandedOver, handedOver);
    c.setWalkUniforms(program);
    c.setLayerUniforms(program, r, d.in.layers);
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
        if (list == ListedPixels::Fresh)
            gl::dispatchIndirect(r.buffer(d.counters), offsetof(WalkCountersGpu, freshGroups));
        else
            gl::dispatchIndirect(handedOver, sizeof(std::uint32_t));
        gl::memoryBarrier(gl::BarrierImage | gl::BarrierStorage | gl::BarrierCommand);
    }
    gl::memoryBarrier(gl::BarrierTexture | gl::BarrierFramebuffer | gl::BarrierBufferUpdate);
    return {};
}

} // namespace refraction
