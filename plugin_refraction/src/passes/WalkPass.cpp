// `refraction.walk`: over the glass pixels (the capture's mask), each pixel's refracted path
// walked through what the capture holds, SIR, ISR or DIR finding each exit (compiled in:
// walk.frag.glsl), and shaded over the copied scene colour; with outlines on, each pixel's
// nearest layer for the outline pass.
#include "Passes.h"

#include <algorithm>
#include <string>
#include <vector>

namespace refraction {

Walked addWalkPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                   const SceneInputs& scene, const Capture& capture) {
    const glm::ivec2 size = c.frame->settings.size;
    struct WalkData {
        Capture capture;
        fg::TextureHandle sceneColor, sceneDepth, out, surface;
        fg::BufferHandle rectangle;
    };
    const bool outlines = c.settings.layered() && c.settings.outlineAntialiasing;
    const auto& walked = graph.addPass<WalkData>(
        "refraction.walk",
        [&](fg::Builder& b, WalkData& d) {
            b.read(buffers.layers);
            b.read(buffers.materials);
            if (c.settings.traces())
                b.read(buffers.distances); // the glass BVH
            for (auto [from, to] : {std::pair{capture.mask, &d.capture.mask},
                                    std::pair{capture.depths0, &d.capture.depths0},
                                    std::pair{capture.depths1, &d.capture.depths1},
                                    std::pair{capture.normals[0], &d.capture.normals[0]},
                                    std::pair{capture.normals[1], &d.capture.normals[1]}})
                if (from.valid())
                    *to = b.read(from);
            d.rectangle = b.write(buffers.rectangle); // counts the overflowing pixels
            d.sceneColor = b.read(scene.color);
            d.sceneDepth = b.read(scene.depth);
            d.out = b.write(b.create("refraction.scene_color", colorDesc(size)));
            if (outlines) // the nearest layer per pixel, for the outline pass
                d.surface =
                    b.write(b.create("refraction.layers.surface", {size, gl::Format::R32UI, 1}));
        },
        [c, outlines](const fg::Resources& r, const WalkData& d, gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            gl::copyTexture(r.texture(d.sceneColor), r.texture(d.out));
            std::vector<const gl::Texture*> targets{&r.texture(d.out)};
            if (outlines)
                targets.push_back(&r.texture(d.surface));
            if (auto bound = gpu.framebuffer.bindTargets("refraction.walk", targets,
                                                         &r.texture(d.capture.mask));
                !bound)
                return bound;
            if (outlines)
                gl::clearColorUint(1, 0u); // no glass
            const gl::Program& program = *c.walk;
            c.setWalkUniforms(program);
            c.setLayerUniforms(program);
            gl::bindTexture(kSceneColorUnit, r.texture(d.sceneColor));
            gl::bindTexture(kSceneDepthUnit, r.texture(d.sceneDepth));
            program.set("uSceneColor", kSceneColorUnit);
            program.set("uSceneDepth", kSceneDepthUnit);
            // The layer depth maps as uLayerDepths0/1 (layers.glsl), the pair's normals as
            // uPairNormals; an absent map: the first depth map stands in (unread).
            const std::pair<const char*, fg::TextureHandle> maps[] = {
                {"uLayerDepths0", d.capture.depths0},
                {"uLayerDepths1", d.capture.depths1},
                {"uPairNormals[0]", d.capture.normals[0]},
                {"uPairNormals[1]", d.capture.normals[1]}};
            int unit = kLayerDepthUnit;
            for (const auto& [uniform, handle] : maps) {
                gl::bindTexture(std::uint32_t(unit),
                                r.texture(handle.valid() ? handle : d.capture.depths0));
                program.set(uniform, unit++);
            }
            if (c.settings.traces()) {
                if (!gpu.glass.bvh)
                    return core::Error{"refraction.walk: the trace has no glass BVH"};
                gpu.glass.bvh->bind(kWalkBvhBinding);
                gl::bindStorage(kWalkBvhBinding + 7, gpu.glass.bvh->uvs()); // walk.frag.glsl
                // The glass normal maps, the first standing in for absent ones (unread).
                const auto& normalMaps = gpu.tracedNormalMaps;
                for (std::size_t i = 0; i < kTracedNormalMaps; ++i) {
                    const std::string name = "uTracedNormalMaps[" + std::to_string(i) + "]";
                    if (!normalMaps.empty())
                        gl::bindTexture(kMaterialUnit + std::uint32_t(i),
                                        *normalMaps[std::min(i, normalMaps.size() - 1)]);
                    program.set(name.c_str(), int(kMaterialUnit + i));
                }
            }
            // The trace's samples one draw each, added up (their weights sum to 1).
            const int draws =
                c.settings.method == Settings::Method::Trace ? c.settings.traceSamples : 1;
            program.set("uTraceWeight", 1.0f / float(draws));
            for (int s = 0; s < draws; ++s) {
                program.set("uTraceSample", s);
                c.drawMaskedRectangle(s == 0 ? gl::Blend::None : gl::Blend::Additive);
            }
            return {};
        });
    buffers.rectangle = walked.rectangle;
    return {walked.out, walked.surface};
}

} // namespace refraction
