// `refraction.front_faces`: the papers' shading pass, every glass item's front faces
// refracted, their exit found and shaded, depth-tested into the glass image
// (front.frag.glsl over glass_shading.glsl).
#include "Passes.h"

namespace refraction {

fg::TextureHandle addFrontFacesPass(fg::FrameGraph& graph, const FrameContext& c,
                                    const SurfaceMaps& maps, const FrameBuffers& buffers,
                                    const SceneInputs& scene) {
    const glm::ivec2 size = c.frame->settings.size;
    const auto& shaded = graph.addPass<TwoSurfaceShadeData>(
        "refraction.front_faces",
        [&](fg::Builder& b, TwoSurfaceShadeData& d) {
            readTwoSurfaceInputs(b, c, maps, buffers, scene, d);
            d.out = b.write(b.create("refraction.glass", colorDesc(size)));
            d.zbuffer = b.write(b.create("refraction.glass_zbuffer", zDesc(size)));
        },
        [c](const fg::Resources& r, const TwoSurfaceShadeData& d, gl::Context&) -> core::Status {
            if (auto bound = c.gpu->framebuffer.bindTargets(
                    "refraction.front_faces", {&r.texture(d.out)}, &r.texture(d.zbuffer));
                !bound)
                return bound;
            gl::clearColor(0, glm::vec4(0.0f));
            gl::clearDepth(1.0f);
            const gl::Program& program = c.gpu->front[c.lit() ? 1 : 0];
            setTwoSurfaceShading(c, program, d, r);
            c.drawGlass(program, {.cull = gl::Cull::Back, .depthFunc = gl::DepthFunc::Less},
                        [&c, &program](const render::DrawItem&, std::size_t index) {
                            c.setMaterial(program, index);
                        });
            return {};
        });
    return shaded.out;
}

} // namespace refraction
