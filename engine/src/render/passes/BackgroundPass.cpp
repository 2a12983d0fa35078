// `background`: the scene targets are created here, with the environment drawn behind all; where
// the frame accumulates, the motion target cleared to the environment's texel (zeros, whose
// motion the resolve works out from the pixel: common/motion.glsl), which costs a CPU rasteriser
// less than a second target the full-screen draw writes.
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace render::passes {

SceneTargets addBackground(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame) {
    const gl::TextureDesc colorDesc{frame.settings.size, gl::Format::RGBA16F, 1};
    const gl::TextureDesc depthDesc{frame.settings.size, gl::Format::Depth32F, 1};
    return graph.addPass<SceneTargets>(
        "background",
        [&](fg::Builder& b, SceneTargets& d) {
            d.color = b.write(b.create("scene.color", colorDesc));
            d.depth = b.write(b.create("scene.depth", depthDesc));
            if (frame.temporal.enabled)
                d.motion = b.write(
                    b.create("scene.motion", {frame.settings.size, gl::Format::RGBA32UI, 1}));
        },
        [&gpu, &frame](const fg::Resources& r, const SceneTargets& d,
                       gl::Context&) -> core::Status {
            auto background = frame.programs->graphics("render/fullscreen.vert.glsl",
                                                       "render/background.frag.glsl");
            if (!background)
                return background.error();
            const gl::Program& program = **background;
            if (auto bound = gpu.framebuffer.bindTargets("background", sceneTargets(r, d),
                                                         &r.texture(d.depth));
                !bound)
                return bound;
            gl::clearDepth(1.0f);
            if (d.motion.valid()) {
                gl::clearColorUint(1, 0u);
                if (auto bound = gpu.framebuffer.bindTargets("background", {&r.texture(d.color)},
                                                             &r.texture(d.depth));
                    !bound)
                    return bound;
            }
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            program.use();
            gpu.environment->bind(program, frame.settings.environmentRotation,
                                  frame.settings.environmentIntensity);
            program.set("uInverseViewProjection", glm::inverse(frame.camera.viewProjection()));
            program.set("uBackgroundBlur", frame.settings.backgroundBlur);
            gpu.emptyVao.bind();
            gl::drawArrays(3);
            return {};
        });
}

} // namespace render::passes
