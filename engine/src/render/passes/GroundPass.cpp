// `ground`: a tiled plane under the characters, lit by the environment and the lights, shadowed.
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace render::passes {

SceneTargets addGround(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                       SceneTargets scene, const fg::Blackboard& blackboard) {
    return graph.addPass<LitTargets>(
        "ground",
        [&](fg::Builder& b, LitTargets& d) {
            d.shadows = ShadowAtlases::readFinal(b, blackboard);
            d.color = b.write(scene.color);
            d.depth = b.write(scene.depth);
            if (scene.motion.valid())
                d.motion = b.write(scene.motion);
        },
        [&gpu, &frame](const fg::Resources& r, const LitTargets& d, gl::Context&) -> core::Status {
            auto ground = frame.programs->graphics("render/ground.vert.glsl",
                                                   "render/ground.frag.glsl", litDefines(frame));
            if (!ground)
                return ground.error();
            if (auto bound =
                    gpu.framebuffer.bindTargets("ground", sceneTargets(r, d), &r.texture(d.depth));
                !bound)
                return bound;
            d.shadows.bind(r, gpu.shadowSampler);
            gl::apply({.cull = gl::Cull::None});
            const gl::Program& p = **ground;
            p.use();
            gpu.environment->bind(p, frame.settings.environmentRotation,
                                  frame.settings.environmentIntensity);
            p.set("uViewProjection", frame.camera.viewProjection());
            p.set("uCameraPosition", frame.camera.position);
            p.set("uCenter", frame.ground.center);
            p.set("uHalfSize", frame.ground.halfSize);
            p.set("uHeight", frame.ground.height);
            p.set("uTileSize", frame.ground.halfSize / 8.0f);
            setMotionUniforms(p, frame);
            gpu.emptyVao.bind();
            gl::drawArrays(6);
            return {};
        });
}

} // namespace render::passes
