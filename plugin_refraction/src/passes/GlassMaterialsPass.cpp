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
        [c](const fg::Resources&, const Data&, gl::Context&) {
            GpuState& gpu = *c.gpu;
            const std::size_t bytes = gpu.glassOptics.size() * sizeof(GlassMaterialGpu);
            if (gpu.glassMaterials.size() < bytes)
                gpu.glassMaterials = gl::Buffer(bytes);
            gpu.glassMaterials.update(0, bytes, gpu.glassOptics.data());
        });
    buffers.materials = pass.materials;
}

} // namespace refraction
