// `deform`: skinning and morphing of every character on the GPU from the frame's one upload of
// skin matrices and morph weights, once, for every later pass.
#include "Passes.h"

namespace render::passes {

fg::BufferHandle addDeform(fg::FrameGraph& graph, RenderGpu& gpu, fg::BufferHandle vertices) {
    struct Data {
        fg::BufferHandle vertices;
    };
    const Data& pass = graph.addPass<Data>(
        "deform", [&](fg::Builder& b, Data& d) { d.vertices = b.write(vertices); },
        [&gpu](const fg::Resources&, const Data&, gl::Context&) {
            for (CharacterGpu& character : gpu.characters)
                character.deformer->dispatch(gpu.poses);
        });
    return pass.vertices;
}

} // namespace render::passes
