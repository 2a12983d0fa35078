// `deform`: skinning and morphing of this frame's pose on the GPU, once, for every later pass.
#include "Passes.h"

namespace render::passes {

fg::BufferHandle addDeform(fg::FrameGraph& graph, RenderGpu& gpu, fg::BufferHandle vertices,
                           const anim::Pose& pose) {
    struct Data {
        fg::BufferHandle vertices;
    };
    const Data& pass = graph.addPass<Data>(
        "deform", [&](fg::Builder& b, Data& d) { d.vertices = b.write(vertices); },
        [&gpu, &pose](const fg::Resources&, const Data&, gl::Context&) {
            gpu.deformer->update(pose);
        });
    return pass.vertices;
}

} // namespace render::passes
