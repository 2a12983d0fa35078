// `deform`: skinning and morphing of this frame's pose on the GPU, once, for every later pass.
#include "Passes.h"

namespace render::passes {

fg::BufferHandle addDeform(fg::FrameGraph& graph, RenderGpu& gpu, fg::BufferHandle vertices,
                           const anim::Pose& pose) {
    struct Data {
        fg::BufferHandle vertices;
    };
    return graph
        .addPass<Data>(
            "deform", [&](fg::Builder& b, Data& d) { d.vertices = b.write(vertices); },
            [&gpu, &pose](const fg::Resources&, const Data&, gl::Context&) {
                gpu.deformer->update(pose);
            })
        .vertices;
}

core::Status bindTargets(RenderGpu& gpu, const char* pass,
                         const std::vector<const gl::Texture*>& colors, const gl::Texture* depth) {
    if (auto attached = gpu.framebuffer.attach(pass, colors, depth); !attached)
        return attached;
    gpu.framebuffer.bind();
    return {};
}

} // namespace render::passes
