// `refraction.resolve`: the gathered targets resolved, over the glass rectangle, into the maps
// the two-surface searches read (back normal, and for TIR the front depth and normal, their
// normals mip-filtered) and the glass pixels' mask (resolve.frag.glsl).
#include "Passes.h"

#include <vector>

namespace refraction {

SurfaceMaps addResolvePass(fg::FrameGraph& graph, const FrameContext& c,
                           const FrameBuffers& buffers, const SceneInputs& scene,
                           const Gathered& gathered) {
    const glm::ivec2 size = c.frame->settings.size;
    struct ResolveData {
        fg::TextureHandle nearTargets, farTargets, sceneDepth, backNormal, frontDepth, frontNormal,
            mask;
    };
    const auto& resolved = graph.addPass<ResolveData>(
        "refraction.resolve",
        [&](fg::Builder& b, ResolveData& d) {
            b.read(buffers.rectangle);
            d.nearTargets = b.read(gathered.nearTargets);
            d.farTargets = b.read(gathered.farTargets);
            d.sceneDepth = b.read(scene.depth);
            d.backNormal = b.write(b.create("refraction.back.normal", normalDesc(size)));
            if (c.reflect) {
                d.frontDepth = b.write(b.create("refraction.front.depth", depthDesc(size)));
                d.frontNormal = b.write(b.create("refraction.front.normal", normalDesc(size)));
            }
            d.mask = b.write(b.create("refraction.glass_mask", zDesc(size)));
        },
        [c](const fg::Resources& r, const ResolveData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            std::vector<const gl::Texture*> targets{&r.texture(d.backNormal)};
            if (c.reflect)
                targets.insert(targets.end(),
                               {&r.texture(d.frontDepth), &r.texture(d.frontNormal)});
            if (auto bound =
                    gpu.framebuffer.bindTargets("refraction.resolve", targets, &r.texture(d.mask));
                !bound)
                return bound;
            // Outside the glass rectangle: no surface, and the mask rejects.
            for (int i = 0; i < int(targets.size()); ++i)
                gl::clearColor(i, glm::vec4(0.0f));
            gl::clearDepth(1.0f);
            gl::apply({.cull = gl::Cull::None, .depthFunc = gl::DepthFunc::Always});
            gpu.resolve.use();
            const std::pair<const char*, fg::TextureHandle> inputs[] = {
                {"uGatherNear", d.nearTargets},
                {"uGatherFar", d.farTargets},
                {"uSceneDepth", d.sceneDepth}};
            int unit = 0;
            for (const auto& [uniform, handle] : inputs) {
                gl::bindTexture(std::uint32_t(unit), r.texture(handle));
                gpu.resolve.set(uniform, unit++);
            }
            gpu.resolve.set("uNear", c.frame->camera.znear);
            gpu.resolve.set("uFar", c.frame->camera.zfar);
            gpu.resolve.set("uViewportSize", glm::vec2(c.frame->settings.size));
            gl::bindStorage(kRectangleBinding, gpu.rectangle);
            gpu.emptyVao.bind();
            gl::drawArrays(6);
            r.texture(d.backNormal).generateMipmaps(); // DIR §3.1: mip-filtered normals
            if (c.reflect) // only TIR bounces toward the front read its normals' mips
                r.texture(d.frontNormal).generateMipmaps();
            return {};
        });
    SurfaceMaps maps;
    maps.backDepth = gathered.nearTargets; // back depth in .r (surfaces.glsl)
    maps.backNormal = resolved.backNormal;
    maps.frontDepth = resolved.frontDepth;
    maps.frontNormal = resolved.frontNormal;
    maps.gatheredFar = gathered.farTargets;
    maps.mask = resolved.mask;
    return maps;
}

} // namespace refraction
