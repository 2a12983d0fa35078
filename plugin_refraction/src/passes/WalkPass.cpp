// `refraction.walk`: over the glass pixels (the capture's mask), each pixel's refracted path
// walked through what the capture holds, SIR, ISR, DIR or the trace finding each exit (compiled
// in: walk.frag.glsl), and shaded over a copy of the scene colour; the hybrid's walk lists the
// pixels the layers cannot represent for its trace pass (HybridTracePass). With outlines on,
// each pixel's nearest layer for the outline pass; where the frame accumulates, a copy of the
// scene's motion with each glass pixel's written over it, and while anything moves the pixels
// whose history will be rejected listed for the fresh samples (FrameContext::freshSamples).
#include "Passes.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace refraction {

namespace {

/** Words of a bit a pixel of a `size` frame. */
std::size_t pixelBitWords(glm::ivec2 size) {
    return (std::size_t(size.x) * std::size_t(size.y) + 31) / 32;
}

/** The hybrid's list of handed-over pixels emptied (no work group, no pixel's bit): count,
 *  work groups (x, y, z), then a bit a pixel and the list. */
void resetHandedOver(gl::Buffer& handedOver, glm::ivec2 size) {
    const std::size_t bits = pixelBitWords(size);
    handedOver.fill(0, 2, 0u);
    handedOver.fill(2 * sizeof(std::uint32_t), 2, 1u);
    handedOver.fill(4 * sizeof(std::uint32_t), bits, 0u);
}

/** The walk's counters zeroed, the fresh samples' work groups (x, y, z) with them; where the
 *  frame takes fresh samples, grown to hold the list of a `size` frame's pixels. */
void resetCounters(gl::Buffer& counters, glm::ivec2 size, bool fresh) {
    const std::size_t bytes =
        sizeof(WalkCountersGpu) +
        (fresh ? std::size_t(size.x) * std::size_t(size.y) * sizeof(std::uint32_t) : 0);
    if (counters.size() < bytes)
        counters = gl::Buffer(bytes);
    counters.fill(0, sizeof(WalkCountersGpu) / sizeof(std::uint32_t), 0u);
    counters.fill(offsetof(WalkCountersGpu, freshGroups) + sizeof(std::uint32_t), 2, 1u);
}

struct WalkData {
    WalkInputs in;
    fg::TextureHandle sceneMotion, historyColor, historyMotion, out, surface, motion;
    fg::BufferHandle counters, handedOver;
};

/** The scene's colour under the glass into the walk's target: a copy, or a conversion where the
 *  walk adds samples up in single precision (in framebuffers kept across frames). */
core::Status copySceneColor(GpuState& gpu, const gl::Texture& sceneColor, const gl::Texture& out) {
    if (sceneColor.desc().format == out.desc().format) {
        gl::copyTexture(sceneColor, out);
        return {};
    }
    if (auto read = gpu.sceneColorRead.attach("refraction.walk", {&sceneColor}, nullptr); !read)
        return read;
    if (auto draw = gpu.framebuffer.attach("refraction.walk", {&out}, nullptr); !draw)
        return draw;
    gpu.framebuffer.blitColorFrom(gpu.sceneColorRead, out.desc().size);
    return {};
}

core::Status walk(const fg::Resources& r, const WalkData& d, const FrameContext& c) {
    // Picked here: the frame's lighting features are known once it is recorded.
    auto walked = c.graphics("refraction/passes/rectangle.vert.glsl",
                             "refraction/passes/walk.frag.glsl", walkDefines(c, c.settings.method));
    if (!walked)
        return walked.error();
    const gl::Program& program = **walked;
    GpuState& gpu = *c.gpu;
    const bool hybrid = c.settings.method == Settings::Method::Hybrid;
    resetCounters(r.buffer(d.counters), c.frame->settings.size, c.freshSamples() > 1);
    const gl::Texture& out = r.texture(d.out);
    if (auto copied = copySceneColor(gpu, r.texture(d.in.sceneColor), out); !copied)
        return copied;
    std::vector<const gl::Texture*> targets{&out};
    if (d.surface.valid())
        targets.push_back(&r.texture(d.surface));
    if (auto bound =
            gpu.framebuffer.bindTargets("refraction.walk", targets, &r.texture(d.in.capture.mask));
        !bound)
        return bound;
    if (d.surface.valid())
        gl::clearColorUint(1, 0u); // no glass
    if (d.motion.valid()) {
        gl::copyTexture(r.texture(d.sceneMotion), r.texture(d.motion));
        gl::bindTexture(gl::slot::kMotion, r.texture(d.sceneMotion));
        gl::bindImage(gl::slot::kMotionImage, r.texture(d.motion), 0, true);
    }
    if (d.historyMotion.valid())
        bindHistory(r, d.historyColor, d.historyMotion);
    if (auto bound = bindWalkInputs(r, c, d.in, d.counters); !bound)
        return bound;
    if (d.handedOver.valid()) {
        resetHandedOver(r.buffer(d.handedOver), c.frame->settings.size);
        gl::bindStorage(slot::kHandedOver, r.buffer(d.handedOver));
    }
    // The trace's and the hybrid's samples one draw each, added up (their weights sum to 1; a
    // debug view shows the first alone); while a frame accumulates, one, and while anything
    // moves the fresh samples' pass takes the later ones where the first lists the pixel.
    const int draws = c.settings.traces() && c.settings.debug == 0 ? c.traceSamples() : 1;
    c.setWalkUniforms(program);
    c.setLayerUniforms(program, r, d.in.layers);
    program.set("uTraceWeight", 1.0f / float(draws));
    for (int s = 0; s < draws; ++s) {
        if (hybrid && s == 1) // the pixels the first handed over
            gl::memoryBarrier(gl::BarrierStorage);
        program.set("uTraceSample", s);
        c.drawMaskedRectangle(r.buffer(d.in.extent),
                              s == 0 ? gl::Blend::None : gl::Blend::Additive);
    }
    // The motion written, for the resolve; the list and counts, for the trace pass.
    // (and the counts and list for their next clear, or layerStats' read back)
    gl::memoryBarrier(gl::BarrierTexture | gl::BarrierImage | gl::BarrierStorage |
                      gl::BarrierCommand | gl::BarrierBufferUpdate);
    return {};
}

} // namespace

Walked addWalkPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                   const SceneInputs& scene, const Capture& capture) {
    const glm::ivec2 size = c.frame->settings.size;
    const auto& walked = graph.addPass<WalkData>(
        "refraction.walk",
        [&](fg::Builder& b, WalkData& d) {
            d.in = readWalkInputs(b, c, buffers, scene, capture);
            d.counters = b.write(buffers.counters);
            // The hybrid's list, bound for its trace pass (and the traced fresh samples').
            if (c.settings.method == Settings::Method::Hybrid ||
                (c.settings.traces() && c.freshSamples() > 1))
                d.handedOver = b.write(b.create(
                    "refraction.handed_over",
                    {(4 + pixelBitWords(size) + std::size_t(size.x) * std::size_t(size.y)) *
                     sizeof(std::uint32_t)}));
            d.out = b.write(b.create("refraction.walk.color", walkDesc(size, c.settings)));
            if (scene.motion.valid()) { // the scene's motion, the glass pixels' written over
                d.sceneMotion = b.read(scene.motion);
                d.motion = b.write(b.create("refraction.motion", {size, gl::Format::RGBA32UI, 1}));
            }
            if (c.freshSamples() > 1) { // which pixels take them, from the history
                d.historyColor = b.read(scene.historyColor);
                d.historyMotion = b.read(scene.historyMotion);
            }
            if (c.settings.outlinePass()) // the nearest layer per pixel, for the outline pass
                d.surface =
                    b.write(b.create("refraction.walk.surface", {size, gl::Format::R32UI, 1}));
        },
        [c](const fg::Resources& r, const WalkData& d, gl::Context&) { return walk(r, d, c); });
    buffers.counters = walked.counters;
    if (walked.handedOver.valid())
        buffers.handedOver = walked.handedOver;
    return {walked.out, walked.surface, walked.motion};
}

} // namespace refraction
