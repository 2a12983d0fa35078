// `refraction.walk`: over the glass pixels (the capture's mask), each pixel's refracted path
// walked through what the capture holds, SIR, ISR, DIR or the trace finding each exit (compiled
// in: walk.frag.glsl), and shaded over the copied scene colour; the hybrid's walk then hands the
// pixels the layers cannot represent to its trace pass (walk_trace.comp.glsl), which shades
// them over that. With outlines on, each pixel's nearest layer for the outline pass; where the
// frame accumulates, a copy of the scene's motion with each glass pixel's written over it.
#include "Passes.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <vector>

namespace refraction {

Walked addWalkPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers,
                   const SceneInputs& scene, const Capture& capture) {
    const glm::ivec2 size = c.frame->settings.size;
    struct WalkData {
        Capture capture;
        fg::TextureHandle sceneColor, sceneDepth, sceneMotion, out, surface, motion;
        fg::BufferHandle rectangle;
    };
    const bool outlines = c.settings.outlinePass();
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
            d.out = b.write(b.create("refraction.scene_color", walkDesc(size, c.settings)));
            if (scene.motion.valid()) { // the scene's motion, the glass pixels' written over
                d.sceneMotion = b.read(scene.motion);
                d.motion = b.write(b.create("refraction.motion", {size, gl::Format::RGBA32UI, 1}));
            }
            if (outlines) // the nearest layer per pixel, for the outline pass
                d.surface =
                    b.write(b.create("refraction.layers.surface", {size, gl::Format::R32UI, 1}));
        },
        [c, outlines, size](const fg::Resources& r, const WalkData& d,
                            gl::Context&) -> core::Status {
            GpuState& gpu = *c.gpu;
            // The scene's colour under the glass: a copy, or a conversion where the walk adds
            // samples up in single precision (in framebuffers kept across frames).
            const gl::Texture &sceneColor = r.texture(d.sceneColor), &out = r.texture(d.out);
            if (sceneColor.desc().format == out.desc().format) {
                gl::copyTexture(sceneColor, out);
            } else {
                if (auto read =
                        gpu.sceneColorRead.attach("refraction.walk", {&sceneColor}, nullptr);
                    !read)
                    return read;
                if (auto draw = gpu.framebuffer.attach("refraction.walk", {&out}, nullptr); !draw)
                    return draw;
                gpu.framebuffer.blitColorFrom(gpu.sceneColorRead, size);
            }
            std::vector<const gl::Texture*> targets{&out};
            if (outlines)
                targets.push_back(&r.texture(d.surface));
            if (auto bound = gpu.framebuffer.bindTargets("refraction.walk", targets,
                                                         &r.texture(d.capture.mask));
                !bound)
                return bound;
            if (outlines)
                gl::clearColorUint(1, 0u); // no glass
            if (d.motion.valid()) {
                gl::copyTexture(r.texture(d.sceneMotion), r.texture(d.motion));
                gl::bindTexture(gl::slot::kMotion, r.texture(d.sceneMotion));
                gl::bindImage(gl::slot::kMotionImage, r.texture(d.motion), 0, true);
            }
            // The walk's inputs; the hybrid's trace pass reads the same (its uniforms by
            // `prepare`): the layer depth maps (layers.glsl), the pair's normals; an absent
            // map: the first depth map stands in (unread).
            gl::bindTexture(slot::kSceneColor, r.texture(d.sceneColor));
            gl::bindTexture(slot::kSceneDepth, r.texture(d.sceneDepth));
            const auto present = [&](fg::TextureHandle h) -> const gl::Texture& {
                return r.texture(h.valid() ? h : d.capture.depths0);
            };
            gl::bindTexture(slot::kLayerDepthMaps, present(d.capture.depths0), 0);
            gl::bindTexture(slot::kLayerDepthMaps, present(d.capture.depths1), 1);
            gl::bindTexture(slot::kPairNormals, present(d.capture.normals[0]), 0);
            gl::bindTexture(slot::kPairNormals, present(d.capture.normals[1]), 1);
            if (c.settings.traces()) {
                if (!gpu.glass.bvh)
                    return core::Error{"refraction.walk: the trace has no glass BVH"};
                gpu.glass.bvh->bindForTraversal();
                // The glass textures, the first standing in for absent ones (unread).
                const auto& textures = gpu.tracedTextures;
                for (std::uint32_t i = 0; i < slot::kTracedTextures.count && !textures.empty(); ++i)
                    gl::bindTexture(slot::kTracedTextures,
                                    *textures[std::min<std::size_t>(i, textures.size() - 1)], i);
            }
            // The trace's and the hybrid's samples (a debug view shows the first alone); one a
            // frame where the frame accumulates.
            const int samples = c.frame->temporal.enabled ? 1 : c.settings.traceSamples;
            const bool hybrid = c.settings.method == Settings::Method::Hybrid;
            const int draws = c.settings.traces() && c.settings.debug == 0 ? samples : 1;
            auto prepare = [&](const gl::Program& program, int weights) {
                c.setWalkUniforms(program);
                c.setLayerUniforms(program);
                program.set("uTraceWeight", 1.0f / float(weights));
            };
            prepare(*c.walk, draws);
            if (hybrid) { // an empty list of handed-over pixels (no work group), no pixel's bit
                const std::size_t pixels = std::size_t(size.x) * std::size_t(size.y);
                const std::size_t bits = (pixels + 31) / 32;
                const std::size_t bytes = (4 + bits + pixels) * sizeof(std::uint32_t);
                if (gpu.handedOver.size() < bytes)
                    gpu.handedOver = gl::Buffer(bytes);
                gpu.handedOver.fill(0, 2, 0u);
                gpu.handedOver.fill(2 * sizeof(std::uint32_t), 2, 1u);
                gpu.handedOver.fill(4 * sizeof(std::uint32_t), bits, 0u);
                gl::bindStorage(slot::kHandedOver, gpu.handedOver);
            }
            // The samples one draw each, added up (their weights sum to 1).
            for (int s = 0; s < draws; ++s) {
                if (hybrid && s == 1) // the pixels the first handed over
                    gl::memoryBarrier(gl::BarrierStorage);
                c.walk->set("uTraceSample", s);
                c.drawMaskedRectangle(s == 0 ? gl::Blend::None : gl::Blend::Additive);
            }
            // The hybrid's handed-over pixels traced over the walk's colour (a debug view shows
            // the walk's own), a dispatch each sample of as many work groups as the walk counted.
            if (!hybrid || c.settings.debug != 0) {
                gl::memoryBarrier(gl::BarrierTexture); // the motion written, for the resolve
                return {};
            }
            gl::memoryBarrier(gl::BarrierStorage | gl::BarrierCommand | gl::BarrierImage);
            prepare(*c.handedOverTrace, samples);
            gl::bindImage(gl::slot::kOutputImage, out, 0, true);
            if (d.motion.valid())
                gl::bindImage(gl::slot::kMotionImage, r.texture(d.motion), 0, true);
            for (int s = 0; s < samples; ++s) {
                c.handedOverTrace->set("uTraceSample", s);
                gl::dispatchIndirect(gpu.handedOver, sizeof(std::uint32_t));
                gl::memoryBarrier(gl::BarrierImage);
            }
            gl::memoryBarrier(gl::BarrierTexture | gl::BarrierFramebuffer);
            return {};
        });
    buffers.rectangle = walked.rectangle;
    return {walked.out, walked.surface, walked.motion};
}

} // namespace refraction
