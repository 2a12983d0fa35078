// `shadow_map_view`: a debug view of one of the frame's shadow atlases in place of the scene
// (RenderSettings::shadowMapView, render/shadow_map_view.frag.glsl), before the tonemap.
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace render::passes {

fg::TextureHandle addShadowMapView(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                                   const ShadowAtlases& shadows) {
    struct Data {
        fg::TextureHandle atlas, color;
    };
    const RenderSettings::ShadowMapView mode = frame.settings.shadowMapView;
    const fg::TextureHandle atlas = mode == RenderSettings::ShadowMapView::Depth ? shadows.depth
                                    : mode == RenderSettings::ShadowMapView::Glass
                                        ? shadows.glass
                                        : shadows.caustics;
    return graph
        .addPass<Data>(
            "shadow_map_view",
            [&](fg::Builder& b, Data& d) {
                d.atlas = b.read(atlas);
                d.color = b.write(b.create("scene.shadow_map_view",
                                           {frame.settings.size, gl::Format::RGBA16F, 1}));
            },
            [&gpu, &frame](const fg::Resources& r, const Data& d, gl::Context&) -> core::Status {
                auto view = frame.programs->graphics("render/fullscreen.vert.glsl",
                                                     "render/shadow_map_view.frag.glsl");
                if (!view)
                    return view.error();
                if (auto bound = gpu.framebuffer.bindTargets("shadow_map_view",
                                                             {&r.texture(d.color)}, nullptr);
                    !bound)
                    return bound;
                gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
                const gl::Program& program = **view;
                program.use();
                gl::bindTexture(gl::slot::kSource, r.texture(d.atlas));
                program.set("uMode", int(frame.settings.shadowMapView));
                program.set("uFrameSize", glm::vec2(frame.settings.size));
                gpu.emptyVao.bind();
                gl::drawArrays(3);
                return {};
            })
        .color;
}

} // namespace render::passes
