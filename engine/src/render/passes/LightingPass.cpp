// `lighting`: the deferred shading of the opaque characters (OpaquePass.cpp draws them into the
// surface targets where the frame has punctual lights): a full-screen triangle at the far plane,
// depth-tested against the scene's depth so that it covers only the pixels a surface is nearer
// at, shaded once each from the targets by the environment and the lights
// (render/lighting.frag.glsl) and added to the emitted light in the colour.
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace render::passes {

fg::TextureHandle addLighting(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                              SceneTargets scene, SurfaceTargets surfaces,
                              const fg::Blackboard& blackboard) {
    struct LightingTargets {
        fg::TextureHandle color, depth;
        SurfaceTargets surfaces;
        ShadowAtlases shadows;
    };
    return graph
        .addPass<LightingTargets>(
            "lighting",
            [&](fg::Builder& b, LightingTargets& d) {
                d.shadows = ShadowAtlases::readFinal(b, blackboard);
                d.depth = b.read(scene.depth);
                for (const fg::TextureHandle surface : surfaces.all())
                    b.read(surface);
                d.surfaces = surfaces;
                d.color = b.write(scene.color);
            },
            [&gpu, &frame](const fg::Resources& r, const LightingTargets& d,
                           gl::Context&) -> core::Status {
                auto program =
                    frame.programs->graphics("render/fullscreen.vert.glsl",
                                             "render/lighting.frag.glsl", frame.lighting.defines());
                if (!program)
                    return program.error();
                // The depth attached for its test alone: the far plane's triangle passes where
                // a surface is nearer.
                if (auto bound = gpu.framebuffer.bindTargets("lighting", {&r.texture(d.color)},
                                                             &r.texture(d.depth));
                    !bound)
                    return bound;
                d.shadows.bind(r, gpu.shadowSampler);
                const auto targets = d.surfaces.all();
                for (std::uint32_t i = 0; i < targets.size(); ++i)
                    gl::bindTexture(gl::slot::kMaterial, r.texture(targets[i]), i);
                gl::apply({.cull = gl::Cull::None,
                           .depthWrite = false,
                           .depthFunc = gl::DepthFunc::Greater,
                           .blend = gl::Blend::Additive});
                const gl::Program& p = **program;
                p.use();
                gpu.environment->bind(p, frame.settings.environmentRotation,
                                      frame.settings.environmentIntensity);
                p.set("uCameraPosition", frame.camera.position);
                gpu.emptyVao.bind();
                gl::drawArrays(3);
                return {};
            })
        .color;
}

} // namespace render::passes
