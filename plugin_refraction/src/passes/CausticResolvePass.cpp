// `refraction.caustic_resolve`: the photons' sums (CausticPhotonsPass.cpp) filtered into the
// caustics atlas the shading reads (caustic_resolve.frag.glsl, common/shadows.glsl;
// docs/materials.md, "Caustics").
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace refraction {

fg::TextureHandle addCausticResolvePass(fg::FrameGraph& graph, const FrameContext& c,
                                        FrameBuffers& buffers) {
    struct Resolve {
        fg::TextureHandle atlas;
        fg::BufferHandle sums;
    };
    const glm::ivec2 size = c.frame->shadows->atlasSize / kCausticScale;
    return graph
        .addPass<Resolve>(
            "refraction.caustic_resolve",
            [&](fg::Builder& b, Resolve& d) {
                d.sums = b.read(buffers.causticSums);
                d.atlas = b.write(b.create("refraction.caustics", {size, gl::Format::RGBA16F, 1}));
            },
            [c](const fg::Resources& r, const Resolve& d, gl::Context&) -> core::Status {
                auto resolve = c.graphics("render/fullscreen.vert.glsl",
                                          "refraction/passes/caustic_resolve.frag.glsl");
                if (!resolve)
                    return resolve.error();
                GpuState& gpu = *c.gpu;
                const gl::Texture& atlas = r.texture(d.atlas);
                if (auto bound = gpu.framebuffer.bindTargets("refraction.caustic_resolve", {&atlas},
                                                             nullptr);
                    !bound)
                    return bound;
                // Texels outside every tile: no caustics, the light straight.
                gl::clearColor(0, glm::vec4(0.0f, 0.0f, 0.0f, render::kNoGlass));
                const gl::Program& program = **resolve;
                program.use();
                setCausticUniforms(program, c);
                gl::bindStorage(slot::kCausticSums, r.buffer(d.sums));
                gl::apply({.cull = gl::Cull::None,
                           .depthTest = false,
                           .depthWrite = false,
                           .blend = gl::Blend::None});
                gpu.emptyVao.bind();
                const render::ShadowPlan& plan = *c.frame->shadows;
                for (std::size_t v = 0; v < plan.views.size(); ++v) {
                    const render::ShadowView& view = plan.views[v];
                    const glm::ivec3 tile = view.tile / kCausticScale;
                    gl::setViewport({tile.x, tile.y, tile.z, tile.z});
                    program.set("uView", int(v));
                    gl::drawArrays(3);
                }
                return {};
            })
        .atlas;
}

} // namespace refraction
