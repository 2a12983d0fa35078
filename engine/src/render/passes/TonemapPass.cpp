// `tonemap`: the HDR scene colour to the display output (exposure, ACES fit, sRGB).
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace render::passes {

void addTonemap(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                fg::TextureHandle scene, fg::TextureHandle output) {
    struct Data {
        fg::TextureHandle scene, output;
    };
    graph.addPass<Data>(
        "tonemap",
        [&](fg::Builder& b, Data& d) {
            d.scene = b.read(scene);
            d.output = b.write(output);
        },
        [&gpu, &frame](const fg::Resources& r, const Data& d, gl::Context&) -> core::Status {
            auto tonemap =
                frame.programs->graphics("render/fullscreen.vert.glsl", "render/tonemap.frag.glsl");
            if (!tonemap)
                return tonemap.error();
            const gl::Program& program = **tonemap;
            if (auto bound =
                    gpu.framebuffer.bindTargets("tonemap", {&r.texture(d.output)}, nullptr);
                !bound)
                return bound;
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            program.use();
            gl::bindTexture(gl::slot::kSource, r.texture(d.scene));
            program.set("uExposure", frame.settings.exposure);
            program.set("uRaw", frame.settings.hdrOutput ? 1 : 0);
            gpu.emptyVao.bind();
            gl::drawArrays(3);
            return {};
        });
}

} // namespace render::passes
