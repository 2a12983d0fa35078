// `refraction.glass_extent`: where the glass lies this frame, from the deformed cages before
// any capture (glass_extent.comp.glsl, a dispatch a glass primitive): its pixel rectangle,
// which the full-screen passes rasterise instead of the screen, and its view-space box, where
// the walk's searches end.
#include "Passes.h"

#include "engine/deform/GpuDeformer.h"

#include <cstddef>
#include <cstdint>

namespace refraction {

void addGlassExtentPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers) {
    struct Data {
        fg::BufferHandle extent;
    };
    const Data& pass = graph.addPass<Data>(
        "refraction.glass_extent",
        [&](fg::Builder& b, Data& d) {
            b.read(buffers.vertices);
            d.extent = b.write(b.create("refraction.extent", {sizeof(GlassExtentGpu)}));
        },
        [c](const fg::Resources& r, const Data& d, gl::Context&) -> core::Status {
            auto grow = c.compute("refraction/passes/glass_extent.comp.glsl");
            if (!grow)
                return grow.error();
            gl::Buffer& extent = r.buffer(d.extent);
            const render::FrameInfo& frame = *c.frame;
            // Empty: min > max (ints for the rectangle, floats as ordered ints for the box).
            using E = GlassExtentGpu;
            extent.fill(offsetof(E, pixelMin), 2, std::uint32_t(INT32_MAX));
            extent.fill(offsetof(E, pixelMax), 2, std::uint32_t(INT32_MIN));
            extent.fill(offsetof(E, boxMin), 3, std::uint32_t(INT32_MAX));
            extent.fill(offsetof(E, boxMax), 3, std::uint32_t(INT32_MIN));
            const gl::Program& program = **grow;
            program.use();
            program.set("uViewportSize", glm::vec2(frame.settings.size));
            gl::bindStorage(slot::kGlassExtent, extent);
            for (const render::DrawItem& item : frame.items) {
                if (!c.isGlass(item))
                    continue;
                program.set("uModelViewProjection", frame.camera.viewProjection() * item.world);
                program.set("uModelView", frame.camera.view * item.world);
                const int count = int(item.primitive->vertexCount());
                program.set("uVertexCount", count);
                gl::bindStorage(gl::slot::kVertices,
                                item.geometry->cage(item.instance, item.primitiveIndex).vertices);
                gl::dispatch(std::uint32_t((count + 63) / 64));
            }
            gl::memoryBarrier(gl::BarrierStorage | gl::BarrierBufferUpdate); // and the next clear
            return core::Status{};
        });
    buffers.extent = pass.extent;
}

} // namespace refraction
