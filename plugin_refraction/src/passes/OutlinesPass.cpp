// `refraction.outlines`: the outlines of smooth glass anti-aliased, over the glass rectangle and
// a pixel around it (the pixels an outline only grazes lie outside the glass:
// outlines.frag.glsl). It reads the walk's colour and writes every pixel there into the scene
// colour, which matches the walk's everywhere else: the frame's colour is copied once, by the
// walk.
#include "Passes.h"

namespace refraction {

fg::TextureHandle addOutlinesPass(fg::FrameGraph& graph, const FrameContext& c,
                                  const FrameBuffers& buffers, const SceneInputs& scene,
                                  const Walked& walked) {
    struct OutlineData {
        fg::TextureHandle shaded, surface, out;
        fg::BufferHandle extent;
    };
    const auto& outlined = graph.addPass<OutlineData>(
        "refraction.outlines",
        [&](fg::Builder& b, OutlineData& d) {
            d.extent = b.read(buffers.extent);
            d.shaded = b.read(walked.color);
            d.surface = b.read(walked.surface);
            d.out = b.write(scene.color);
        },
        [c](const fg::Resources& r, const OutlineData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            if (auto bound = gpu.framebuffer.bindTargets("refraction.outlines", {&r.texture(d.out)},
                                                         nullptr);
                !bound)
                return bound;
            auto outlines = c.graphics("refraction/passes/rectangle.vert.glsl",
                                       "refraction/passes/outlines.frag.glsl");
            if (!outlines)
                return outlines.error();
            const gl::Program& program = **outlines;
            program.use();
            program.set("uViewportSize", glm::vec2(c.frame->settings.size));
            program.set("uRectangleMargin", 1.0f);
            gl::bindTexture(slot::kSceneColor, r.texture(d.shaded));
            gl::bindTexture(slot::kOutlineSurface, r.texture(d.surface));
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            c.drawRectangle(r.buffer(d.extent));
            return {};
        });
    return outlined.out;
}

} // namespace refraction
