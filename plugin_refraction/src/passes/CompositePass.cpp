// `refraction.composite`: the glass image of the front faces over the scene colour
// (composite.frag.glsl).
#include "Passes.h"

namespace refraction {

fg::TextureHandle addCompositePass(fg::FrameGraph& graph, const FrameContext& c,
                                   const SceneInputs& scene, fg::TextureHandle glass) {
    const glm::ivec2 size = c.frame->settings.size;
    struct CompositeData {
        fg::TextureHandle scene, glass, out;
    };
    const auto& composite = graph.addPass<CompositeData>(
        "refraction.composite",
        [&](fg::Builder& b, CompositeData& d) {
            d.scene = b.read(scene.color);
            d.glass = b.read(glass);
            d.out = b.write(b.create("refraction.scene_color", colorDesc(size)));
        },
        [c](const fg::Resources& r, const CompositeData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            if (auto bound = gpu.framebuffer.bindTargets("refraction.composite",
                                                         {&r.texture(d.out)}, nullptr);
                !bound)
                return bound;
            gl::apply({.cull = gl::Cull::None, .depthTest = false, .depthWrite = false});
            gpu.composite.use();
            gl::bindTexture(0, r.texture(d.scene));
            gl::bindTexture(1, r.texture(d.glass));
            gpu.composite.set("uScene", 0);
            gpu.composite.set("uGlass", 1);
            gpu.emptyVao.bind();
            gl::drawArrays(3);
            return {};
        });
    return composite.out;
}

} // namespace refraction
