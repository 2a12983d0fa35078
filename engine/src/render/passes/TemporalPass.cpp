// `temporal`: the frame blended into the history the renderer keeps across frames
// (render/temporal.frag.glsl), which the tonemap then reads; the frame's motion copied into the
// history for the next frame's checks.
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace render::passes {

fg::TextureHandle addTemporal(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                              TemporalHistory& history, fg::TextureHandle color,
                              fg::TextureHandle motion, fg::TextureHandle previousColor,
                              fg::TextureHandle previousMotion) {
    struct Data {
        fg::TextureHandle color, motion, previousColor, previousMotion, nextColor, nextMotion, view;
    };
    const fg::TextureHandle nextColor =
        graph.importTexture("history.color.next", history.nextColor().desc(), &history.nextColor());
    const fg::TextureHandle nextMotion = graph.importTexture(
        "history.motion.next", history.nextMotion().desc(), &history.nextMotion());
    const bool view = frame.settings.temporal.view != TemporalSettings::View::Off;
    const Data& resolved = graph.addPass<Data>(
        "temporal",
        [&](fg::Builder& b, Data& d) {
            d.color = b.read(color);
            d.motion = b.read(motion);
            d.previousColor = b.read(previousColor);
            d.previousMotion = b.read(previousMotion);
            d.nextColor = b.write(nextColor);
            d.nextMotion = b.write(nextMotion);
            if (view)
                d.view = b.write(
                    b.create("temporal.view", {frame.settings.size, gl::Format::RGBA16F, 1}));
        },
        [&gpu, &frame](const fg::Resources& r, const Data& d, gl::Context&) -> core::Status {
            // The resolve's variant for the frame's history (temporal.frag.glsl).
            const TemporalSettings& s = frame.settings.temporal;
            const bool still = frame.temporal.still && s.convergeStill;
            auto resolve = frame.programs->graphics(
                "render/fullscreen.vert.glsl", "render/temporal.frag.glsl",
                {std::string("TEMPORAL_STILL ") + (still ? "1" : "0"),
                 std::string("TEMPORAL_REJECT ") + (s.rejectHistory ? "1" : "0"),
                 "TEMPORAL_VIEW " + std::to_string(int(s.view))});
            if (!resolve)
                return resolve.error();
            std::vector<const gl::Texture*> targets{&r.texture(d.nextColor)};
            if (d.view.valid())
                targets.push_back(&r.texture(d.view));
            if (auto bound = gpu.framebuffer.bindTargets("temporal", targets, nullptr); !bound)
                return bound;
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            const gl::Program& p = **resolve;
            p.use();
            gl::bindTexture(gl::slot::kSource, r.texture(d.color));
            gl::bindTexture(gl::slot::kMotion, r.texture(d.motion));
            gl::bindTexture(gl::slot::kHistory, r.texture(d.previousColor), 0);
            gl::bindTexture(gl::slot::kHistory, r.texture(d.previousMotion), 1);
            setMotionUniforms(p, frame);
            p.set("uIndex", int(frame.temporal.index));
            p.set("uHistoryWeight", s.historyWeight);
            gpu.emptyVao.bind();
            gl::drawArrays(3);
            // The motion the next frame checks its history against: this frame's, copied
            // (a copy costs less than a 16-byte target on a CPU rasteriser).
            gl::copyTexture(r.texture(d.motion), r.texture(d.nextMotion));
            return {};
        });
    return view ? resolved.view : resolved.nextColor;
}

} // namespace render::passes
