// `refraction.layer_outlines`: the outlines of smooth glass anti-aliased, over the glass
// rectangle and a pixel around it (the pixels an outline only grazes lie outside the glass:
// layers_outline.frag.glsl).
#include "Passes.h"

namespace refraction {

fg::TextureHandle addLayerOutlinePass(fg::FrameGraph& graph, const FrameContext& c,
                                      const FrameBuffers& buffers, const Walked& shaded) {
    const glm::ivec2 size = c.frame->settings.size;
    struct OutlineData {
        fg::TextureHandle shaded, surface, out;
        fg::BufferHandle rectangle;
    };
    const auto& outlined = graph.addPass<OutlineData>(
        "refraction.layer_outlines",
        [&](fg::Builder& b, OutlineData& d) {
            d.rectangle = b.read(buffers.rectangle);
            d.shaded = b.read(shaded.color);
            d.surface = b.read(shaded.surface);
            // The walk's format (a copy of its colour, then the outlines over it).
            d.out = b.write(b.create("refraction.scene_color", walkDesc(size, c.settings)));
        },
        [c](const fg::Resources& r, const OutlineData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            gl::copyTexture(r.texture(d.shaded), r.texture(d.out));
            if (auto bound = gpu.framebuffer.bindTargets("refraction.layer_outlines",
                                                         {&r.texture(d.out)}, nullptr);
                !bound)
                return bound;
            const gl::Program& program = gpu.layersOutline;
            program.use();
            program.set("uViewportSize", glm::vec2(c.frame->settings.size));
            program.set("uRectangleMargin", 1.0f);
            gl::bindTexture(slot::kSceneColor, r.texture(d.shaded));
            gl::bindTexture(slot::kOutlineSurface, r.texture(d.surface));
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            c.drawRectangle();
            return {};
        });
    return outlined.out;
}

} // namespace refraction
