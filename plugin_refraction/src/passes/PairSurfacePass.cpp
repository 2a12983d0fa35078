// `refraction.pair_surface.back` and `.front`: the pair capture drawn as the papers' two
// geometry passes, the back faces (farthest, or first) and the nearest front faces, each into a
// depth map (with d_N) and a mip-filtered normal map (with the glass id), and where the frame's
// glass is textured a map of its surfaces, under its own depth test (pair_surface.frag.glsl).
#include "Passes.h"

#include <string>
#include <vector>

namespace refraction {

PairTargets addPairSurfacePasses(fg::FrameGraph& graph, const FrameContext& c,
                                 const FrameBuffers& buffers, bool firstBack) {
    struct SurfaceData {
        fg::TextureHandle depth, normal, surface, zbuffer; // surface: with textured glass
        GlassDrawn glass;
    };
    const glm::ivec2 size = c.frame->settings.size;
    // Farthest: GREATER from 0; nearest: LESS from 1.
    auto surfacePass = [&](const char* name, bool backFaces, bool nearest) -> const SurfaceData& {
        return graph.addPass<SurfaceData>(
            name,
            [&](fg::Builder& b, SurfaceData& d) {
                d.glass = readGlassDrawn(b, c, buffers);
                // The front's motion rides in z and w where the frame accumulates.
                const bool motion = !backFaces && c.frame->temporal.enabled;
                d.depth =
                    b.write(b.create(std::string(name) + ".depth",
                                     {size, motion ? gl::Format::RGBA32F : gl::Format::RG32F, 1}));
                d.normal = b.write(b.create(std::string(name) + ".normal", normalDesc(size)));
                if (c.texturedGlass)
                    d.surface = b.write(
                        b.create(std::string(name) + ".surface", {size, gl::Format::RG32UI, 1}));
                d.zbuffer = b.write(b.create(std::string(name) + ".zbuffer", zDesc(size)));
            },
            [c, backFaces, nearest, name](const fg::Resources& r, const SurfaceData& d,
                                          gl::Context&) -> core::Status {
                auto program = c.graphics(
                    "refraction/passes/glass.vert.glsl", "refraction/passes/pair_surface.frag.glsl",
                    concat(c.glassModel, {define("WRITE_MOTION", c.frame->temporal.enabled)}));
                if (!program)
                    return program.error();
                std::vector<const gl::Texture*> targets{&r.texture(d.depth), &r.texture(d.normal)};
                if (d.surface.valid())
                    targets.push_back(&r.texture(d.surface));
                if (auto bound =
                        c.gpu->framebuffer.bindTargets(name, targets, &r.texture(d.zbuffer));
                    !bound)
                    return bound;
                gl::clearColor(0, glm::vec4(0.0f));
                gl::clearColor(1, glm::vec4(0.0f));
                if (d.surface.valid())
                    gl::clearColorUint(2, 0u);
                gl::clearDepth(nearest ? 1.0f : 0.0f);
                c.drawGlassMaterials(
                    **program,
                    {.cull = backFaces ? gl::Cull::Front : gl::Cull::Back,
                     .depthFunc = nearest ? gl::DepthFunc::Less : gl::DepthFunc::Greater},
                    r, d.glass);
                // DIR §3.1: mip-filtered normals (the front's only for TIR bounces toward it)
                if (backFaces || c.reflect)
                    r.texture(d.normal).generateMipmaps();
                return {};
            });
    };
    const SurfaceData& back = surfacePass("refraction.pair_surface.back", true, firstBack);
    const SurfaceData& front = surfacePass("refraction.pair_surface.front", false, true);
    PairTargets pair;
    pair.frontDepth = front.depth;
    pair.frontNormal = front.normal;
    pair.backDepth = back.depth;
    pair.backNormal = back.normal;
    pair.frontSurface = front.surface;
    pair.backSurface = back.surface;
    return pair;
}

} // namespace refraction
