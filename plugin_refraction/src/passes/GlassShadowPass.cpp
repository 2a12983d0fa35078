// `refraction.glass_shadow`: every glass item from each shadow view of
// the frame's lights into its tile of the engine's glass atlas, blended (optical depth added,
// the nearest distance kept: glass_shadow.frag.glsl), so that light through the glass reaches
// what lies behind it tinted by Fresnel, base colour, transmission and Beer-Lambert over the
// distance it crosses, in a straight line (docs/materials.md, "Shadows"). With the caustics, it
// also marks the texels of the caustics atlas whose light meets glass, where the photons start.
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace refraction {

namespace {

/** Words of the emitters' header for an atlas of `texels`: the count and the passes' work
 *  groups, then a bit a texel (caustics.glsl). */
std::size_t emitterHeader(std::size_t texels) {
    return 8 + (texels + 31) / 32;
}

/** The caustics' storage for an atlas of `size` texels and `photons` photons a frame: the
 *  emitters, their header then the photon list (at most a photon a cell of the grid where
 *  cells are wider than a texel, at most the budget, and a rounding's one, where they are a
 *  texel); the sums, four words a cell for as many fine cells as texels and again for the
 *  coarse. */
void createCaustics(fg::Builder& b, FrameBuffers& buffers, glm::ivec2 size, int photons) {
    const std::size_t texels = std::size_t(size.x) * std::size_t(size.y);
    const std::size_t listed = texels + std::size_t(photons) + std::size_t(photons) / 1000 + 1;
    buffers.causticEmitters = b.write(b.create(
        "refraction.caustic_emitters", {sizeof(std::uint32_t) * (emitterHeader(texels) + listed)}));
    buffers.causticSums = b.write(b.create("refraction.caustic_sums", {2 * 16 * texels}));
}

} // namespace

fg::TextureHandle addGlassShadowPass(fg::FrameGraph& graph, const FrameContext& c,
                                     FrameBuffers& buffers, fg::TextureHandle atlas) {
    struct Data {
        fg::TextureHandle atlas;
        fg::BufferHandle emitters, sums;
        GlassDrawn glass;
    };
    const Data& pass = graph.addPass<Data>(
        "refraction.glass_shadow",
        [&](fg::Builder& b, Data& d) {
            d.glass = readGlassDrawn(b, c, buffers);
            d.atlas = b.write(atlas);
            if (c.caustics) {
                createCaustics(b, buffers, causticSize(c), c.settings.causticPhotons);
                d.emitters = buffers.causticEmitters;
                d.sums = buffers.causticSums;
            }
        },
        [c](const fg::Resources& r, const Data& d, gl::Context&) -> core::Status {
            // textured glass, the caustics' emitters
            auto shadow = c.graphics(
                "refraction/passes/glass.vert.glsl", "refraction/passes/glass_shadow.frag.glsl",
                concat(c.glassModel, {"PUNCTUAL_LIGHTS 0", "WRITE_MOTION 0",
                                      define("CAUSTIC_EMITTERS", c.caustics)}));
            if (!shadow)
                return shadow.error();
            GpuState& gpu = *c.gpu;
            if (auto bound = gpu.framebuffer.bindTargets("refraction.glass_shadow",
                                                         {&r.texture(d.atlas)}, nullptr);
                !bound)
                return bound;
            const gl::Program& program = **shadow;
            program.use();
            program.set("uFresnelMode", int(c.settings.fresnel));
            if (c.caustics) { // emptied: no emitter, no light summed
                const glm::ivec2 size = causticSize(c);
                gl::Buffer& emitters = r.buffer(d.emitters);
                gl::Buffer& sums = r.buffer(d.sums);
                emitters.fill(0, emitterHeader(std::size_t(size.x) * std::size_t(size.y)), 0u);
                sums.fill(0, sums.size() / sizeof(std::uint32_t), 0u);
                program.set("uCausticSize", size);
                gl::bindStorage(slot::kCausticEmitters, emitters);
                gl::bindStorage(slot::kCausticSums, sums); // declared, unwritten
            }
            for (const render::ShadowView& view : c.frame->shadows->views) {
                gl::setViewport({view.tile.x, view.tile.y, view.tile.z, view.tile.z});
                program.set("uPerspective", view.perspective ? 1 : 0);
                program.set("uNear", view.near);
                c.drawGlassMaterials(program,
                                     {.cull = gl::Cull::None,
                                      .depthTest = false,
                                      .depthWrite = false,
                                      .blend = gl::Blend::AddMinAlpha},
                                     r, d.glass, GlassView{view.view, view.projection});
            }
            if (c.caustics) // the emitters, for the photons and the next frame's clear
                gl::memoryBarrier(gl::BarrierStorage | gl::BarrierBufferUpdate);
            return {};
        });
    return pass.atlas;
}

} // namespace refraction
