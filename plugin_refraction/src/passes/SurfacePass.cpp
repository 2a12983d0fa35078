// `refraction.back_faces` and `refraction.front_depth`: the papers' geometry passes, the back
// faces (farthest, or first) and, for TIR reflection, the nearest front faces, each into a
// depth and a mip-filtered normal map (surface.frag.glsl).
#include "Passes.h"

#include <string>

namespace refraction {

SurfaceMaps addSurfacePasses(fg::FrameGraph& graph, const FrameContext& c,
                             const FrameBuffers& buffers, bool firstBack) {
    struct SurfaceData {
        fg::TextureHandle depth, normal, zbuffer;
    };
    const glm::ivec2 size = c.frame->settings.size;
    // Farthest: GREATER from 0; nearest: LESS from 1.
    auto surfacePass = [&](const char* name, bool backFaces, bool nearest) -> const SurfaceData& {
        return graph.addPass<SurfaceData>(
            name,
            [&](fg::Builder& b, SurfaceData& d) {
                b.read(buffers.vertices);
                if (c.settings.usesNormalDistance())
                    b.read(buffers.distances);
                d.depth = b.write(b.create(std::string(name) + ".depth", depthDesc(size)));
                d.normal = b.write(b.create(std::string(name) + ".normal", normalDesc(size)));
                d.zbuffer = b.write(b.create(std::string(name) + ".zbuffer", zDesc(size)));
            },
            [c, backFaces, nearest, name](const fg::Resources& r, const SurfaceData& d,
                                          gl::Context&) -> core::Status {
                if (auto bound = c.gpu->framebuffer.bindTargets(
                        name, {&r.texture(d.depth), &r.texture(d.normal)}, &r.texture(d.zbuffer));
                    !bound)
                    return bound;
                gl::clearColor(0, glm::vec4(0.0f));
                gl::clearColor(1, glm::vec4(0.0f));
                gl::clearDepth(nearest ? 1.0f : 0.0f);
                c.drawGlass(c.gpu->surface,
                            {.cull = backFaces ? gl::Cull::Front : gl::Cull::Back,
                             .depthFunc = nearest ? gl::DepthFunc::Less : gl::DepthFunc::Greater});
                r.texture(d.normal).generateMipmaps(); // DIR §3.1: mip-filtered normals
                return {};
            });
    };
    SurfaceMaps maps;
    if (c.settings.twoInterfaces()) {
        const SurfaceData& back = surfacePass("refraction.back_faces", true, firstBack);
        maps.backDepth = back.depth;
        maps.backNormal = back.normal;
    }
    if (c.reflect) {
        const SurfaceData& front = surfacePass("refraction.front_depth", false, true);
        maps.frontDepth = front.depth;
        maps.frontNormal = front.normal;
    }
    return maps;
}

} // namespace refraction
