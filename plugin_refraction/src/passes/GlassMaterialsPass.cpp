// `refraction.glass_materials`: the frame's glass optics, one entry per glass id, into the
// storage buffer every shading pass reads (glass_materials.glsl).
#include "Passes.h"

namespace refraction {

void addGlassMaterialsPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers) {
    struct Data {
        fg::BufferHandle materials;
    };
    const Data& pass = graph.addPass<Data>(
        "refraction.glass_materials",
        [&](fg::Builder& b, Data& d) { d.materials = b.write(buffers.materials); },
        [c](const fg::Resources& r, const Data& d, gl::Context&) {
            const std::vector<GlassMaterialGpu>& optics = c.gpu->glassOptics;
            const std::size_t bytes = optics.size() * sizeof(GlassMaterialGpu);
            gl::Buffer& materials = r.buffer(d.materials); // grown as needed
            if (materials.size() < bytes)
                materials = gl::Buffer(bytes);
            materials.update(0, bytes, optics.data());
        });
    buffers.materials = pass.materials;
}

} // namespace refraction
