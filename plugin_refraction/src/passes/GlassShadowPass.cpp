// `refraction.glass_shadow` (plugin::Stage::Shadows): every glass item from each shadow view of
// the frame's lights into its tile of the engine's glass atlas, blended (optical depth added,
// the nearest distance kept: glass_shadow.frag.glsl), so that light through the glass reaches
// what lies behind it tinted by Fresnel, base colour, transmission and Beer-Lambert over the
// distance it crosses, in a straight line (docs/materials.md, "Shadows"). With the caustics, it
// also marks the texels of the caustics atlas whose light meets glass, where the photons start.
#include "Passes.h"

#include "engine/gl/Commands.h"

namespace refraction {

namespace {

/** The caustics' storage sized for an atlas of `size` texels and `photons` photons a frame
 *  (grown, never shrunk), the emitters and the sums cleared. */
void resetCaustics(GpuState::Caustics& caustics, glm::ivec2 size, int photons) {
    const std::size_t texels = std::size_t(size.x) * std::size_t(size.y);
    // The count and the passes' work groups, a bit a texel, then the photon list
    // (caustics.glsl): at most a photon a cell of the grid where cells are wider than a texel,
    // at most the budget (and a rounding's one) where they are a texel.
    const std::size_t header = 8 + (texels + 31) / 32;
    const std::size_t listed = texels + std::size_t(photons) + std::size_t(photons) / 1000 + 1;
    const std::size_t emitterBytes = 4 * (header + listed), sumBytes = 2 * 16 * texels;
    // The sums: four words a cell, for as many fine cells as texels and again for the coarse.
    if (caustics.emitters.size() < emitterBytes)
        caustics.emitters = gl::Buffer(emitterBytes);
    if (caustics.sums.size() < sumBytes)
        caustics.sums = gl::Buffer(sumBytes);
    caustics.size = size;
    caustics.emitters.fill(0, header, 0u); // the list is written before it is read
    caustics.sums.fill(0, sumBytes / 4, 0u);
}

} // namespace

fg::TextureHandle addGlassShadowPass(fg::FrameGraph& graph, const FrameContext& c,
                                     FrameBuffers& buffers, fg::TextureHandle atlas) {
    struct Data {
        fg::TextureHandle atlas;
        fg::BufferHandle caustics;
    };
    const Data& pass = graph.addPass<Data>(
        "refraction.glass_shadow",
        [&](fg::Builder& b, Data& d) {
            b.read(buffers.vertices);
            b.read(buffers.materials);
            d.atlas = b.write(atlas);
            if (c.caustics)
                d.caustics = b.write(buffers.caustics);
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
            if (c.caustics) {
                resetCaustics(gpu.caustics, c.frame->shadows->atlasSize / kCausticScale,
                              c.settings.causticPhotons);
                program.set("uCausticSize", gpu.caustics.size);
                gl::bindStorage(slot::kCausticEmitters, gpu.caustics.emitters);
                gl::bindStorage(slot::kCausticSums, gpu.caustics.sums); // declared, unwritten
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
                                     GlassView{view.view, view.projection});
            }
            if (c.caustics) // the emitters, for the photons and the next frame's clear
                gl::memoryBarrier(gl::BarrierStorage | gl::BarrierBufferUpdate);
            return {};
        });
    if (c.caustics)
        buffers.caustics = pass.caustics;
    return pass.atlas;
}

} // namespace refraction
