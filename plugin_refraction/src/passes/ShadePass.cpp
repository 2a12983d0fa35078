// `refraction.shade`: after the gathered geometry pass, the scene colour copied and one pass over
// the glass rectangle shades the glass pixels (the mask's early depth test skips the others;
// deferred.frag.glsl over glass_shading.glsl).
#include "Passes.h"

namespace refraction {

fg::TextureHandle addShadePass(fg::FrameGraph& graph, const FrameContext& c,
                               const SurfaceMaps& maps, const FrameBuffers& buffers,
                               const SceneInputs& scene) {
    const glm::ivec2 size = c.frame->settings.size;
    const auto& shaded = graph.addPass<TwoSurfaceShadeData>(
        "refraction.shade",
        [&](fg::Builder& b, TwoSurfaceShadeData& d) {
            readTwoSurfaceInputs(b, c, maps, buffers, scene, d);
            d.out = b.write(b.create("refraction.scene_color", colorDesc(size)));
        },
        [c](const fg::Resources& r, const TwoSurfaceShadeData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            gl::copyTexture(r.texture(d.sceneColor), r.texture(d.out));
            if (auto bound = gpu.framebuffer.bindTargets("refraction.shade", {&r.texture(d.out)},
                                                         &r.texture(d.maps.mask));
                !bound)
                return bound;
            const gl::Program& program = gpu.deferred[c.lit() ? 1 : 0];
            setTwoSurfaceShading(c, program, d, r);
            c.setMaterial(program, c.glassIndex);
            gl::bindTexture(kGatherFarUnit, r.texture(d.maps.gatheredFar));
            program.set("uGatherFar", int(kGatherFarUnit));
            c.drawMaskedRectangle();
            return {};
        });
    return shaded.out;
}

} // namespace refraction
