// `shadows`: the frame's shadow atlases (render/Shadows.h): every opaque draw item from each
// shadow view into its tile of the depth atlas; the glass atlas cleared for the plugins that
// draw their glass into it. The frame's shading passes read the atlases as the plugins leave
// them, and bind them (render::ShadowAtlases).
#include "Passes.h"

#include "engine/gl/Commands.h"

#include <algorithm>

namespace render::passes {

ShadowAtlases addShadows(fg::FrameGraph& graph, RenderGpu& gpu, const FrameInfo& frame,
                         fg::BufferHandle vertices) {
    const ShadowPlan& plan = *frame.shadows;
    return graph.addPass<ShadowAtlases>(
        "shadows",
        [&](fg::Builder& b, ShadowAtlases& d) {
            b.read(vertices);
            d.depth =
                b.write(b.create("scene.shadow_depth", {plan.atlasSize, gl::Format::Depth32F, 1}));
            // Full size where a plugin draws items (its glass may cast into it), else 1 x 1.
            const bool claimed = std::any_of(frame.items.begin(), frame.items.end(),
                                             [](const DrawItem& item) { return item.owner; });
            d.glass =
                b.write(b.create("scene.shadow_glass", {claimed ? plan.atlasSize : glm::ivec2(1),
                                                        gl::Format::RGBA16F, 1}));
        },
        [&gpu, &frame, &plan](const fg::Resources& r, const ShadowAtlases& d,
                              gl::Context&) -> core::Status {
            auto caster =
                frame.programs->graphics("render/shadows.vert.glsl", "render/shadows.frag.glsl");
            if (!caster)
                return caster.error();
            const gl::Program& program = **caster;
            const gl::Texture& depth = r.texture(d.depth);
            const gl::Texture& glass = r.texture(d.glass);
            if (auto bound = gpu.framebuffer.bindTargets("shadows", {&glass}, nullptr); !bound)
                return bound;
            gl::clearColor(0, glm::vec4(0.0f, 0.0f, 0.0f, kNoGlass)); // no glass: none in front
            if (auto bound = gpu.framebuffer.bindTargets("shadows", {}, &depth); !bound)
                return bound;
            gl::clearDepth(1.0f);
            program.use();
            for (const ShadowView& view : plan.views) {
                gl::setViewport({view.tile.x, view.tile.y, view.tile.z, view.tile.z});
                program.set("uViewProjection", view.viewProjection());
                for (const DrawItem& item : frame.items) {
                    if (item.owner)
                        continue;
                    // Pushed back by their slope: no acne. A closed surface's front faces hold
                    // its nearest depth along every ray from the light, so its back faces are
                    // left out (half the triangles to set up); an open one draws both sides.
                    gl::apply({.cull = item.gpu->closed ? gl::Cull::Back : gl::Cull::None,
                               .clockwise = item.mirrored,
                               .depthBiasSlope = 2.0f,
                               .depthBiasUnits = 4.0f});
                    program.set("uModel", item.world);
                    gl::bindStorage(gl::slot::kVertices, *item.gpu->deformed);
                    item.vertexArray->bind();
                    gl::drawIndexed(item.gpu->indexCount);
                }
            }
            return {};
        });
}

} // namespace render::passes
