// `refraction.glass_shadow` (plugin::Stage::Shadows): every glass item from each shadow view of
// the frame's lights into its tile of the engine's glass atlas, blended (optical depth added,
// the nearest distance kept: glass_shadow.frag.glsl), so that light through the glass reaches
// what lies behind it tinted by Fresnel, base colour, transmission and Beer-Lambert over the
// distance it crosses, in a straight line (docs/materials.md, "Shadows").
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace refraction {

fg::TextureHandle addGlassShadowPass(fg::FrameGraph& graph, const FrameContext& c,
                                     const FrameBuffers& buffers, fg::TextureHandle atlas) {
    struct Data {
        fg::TextureHandle atlas;
    };
    return graph
        .addPass<Data>(
            "refraction.glass_shadow",
            [&](fg::Builder& b, Data& d) {
                b.read(buffers.vertices);
                b.read(buffers.materials);
                d.atlas = b.write(atlas);
            },
            [c](const fg::Resources& r, const Data& d, gl::Context&) -> core::Status {
                GpuState& gpu = *c.gpu;
                if (auto bound = gpu.framebuffer.bindTargets("refraction.glass_shadow",
                                                             {&r.texture(d.atlas)}, nullptr);
                    !bound)
                    return bound;
                const gl::Program& program = gpu.glassShadow;
                program.use();
                program.set("uFresnelMode", int(c.settings.fresnel));
                for (const render::ShadowView& view : c.frame->shadows->views) {
                    gl::setViewport({view.tile.x, view.tile.y, view.tile.z, view.tile.z});
                    program.set("uPerspective", view.perspective ? 1 : 0);
                    program.set("uNear", view.near);
                    c.drawGlassMaterials(program,
                                         {.cull = gl::Cull::None,
                                          .depthTest = false,
                                          .depthWrite = false,
                                          .blend = gl::Blend::AddMinAlpha},
                                         GlassView{view.view, view.projection});
                }
                return {};
            })
        .atlas;
}

} // namespace refraction
