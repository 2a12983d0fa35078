// `refraction.depth_range`: the nearest and farthest depth of the back (and front) map, which
// bound the two-surface searches (depth_range.comp.glsl).
#include "Passes.h"

#include <cstddef>

namespace refraction {

void addDepthRangePass(fg::FrameGraph& graph, const FrameContext& c, const SurfaceMaps& maps,
                       FrameBuffers& buffers) {
    struct RangeData {
        fg::TextureHandle back, front;
        fg::BufferHandle rectangle, range;
    };
    const auto& ranged = graph.addPass<RangeData>(
        "refraction.depth_range",
        [&](fg::Builder& b, RangeData& d) {
            // reads the glass rectangle, or (separate passes) sets it to the screen
            d.rectangle = b.write(buffers.rectangle);
            d.range = b.write(buffers.range);
            d.back = b.read(maps.backDepth);
            if (c.reflect)
                d.front = b.read(maps.frontDepth);
        },
        [c](const fg::Resources& r, const RangeData& d, gl::Context&) {
            GpuState& gpu = *c.gpu;
            const glm::ivec2 size = c.frame->settings.size;
            for (std::size_t slot = 0; slot < 2; ++slot) { // min: FLT_MAX bits, max: 0
                gpu.range.fill(8 * slot, 1, 0x7F7FFFFFu);
                gpu.range.fill(8 * slot + 4, 1, 0u);
            }
            if (!c.onePass) { // the separate passes grow no glass rectangle: the screen
                using R = GlassRectangleGpu;
                gpu.rectangle.fill(offsetof(R, pixelMin), 2, 0u);
                gpu.rectangle.fill(offsetof(R, pixelMax), 1, std::uint32_t(size.x - 1));
                gpu.rectangle.fill(offsetof(R, pixelMax) + 4, 1, std::uint32_t(size.y - 1));
            }
            gpu.depthRange.use();
            gl::bindStorage(0, gpu.range); // depth_range.comp.glsl
            gl::bindStorage(kRectangleBinding, gpu.rectangle);
            for (int slot = 0; slot < (d.front.valid() ? 2 : 1); ++slot) {
                gl::bindTexture(0, r.texture(slot == 0 ? d.back : d.front));
                gpu.depthRange.set("uDepth", 0);
                gpu.depthRange.set("uSlot", slot);
                gl::dispatch(std::uint32_t((size.x + 63) / 64), std::uint32_t((size.y + 63) / 64));
            }
            gl::memoryBarrier(gl::BarrierStorage);
        });
    buffers.rectangle = ranged.rectangle;
    buffers.range = ranged.range;
}

} // namespace refraction
