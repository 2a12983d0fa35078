// The layer arrays' sizes (layers.glsl): what they hold a pixel, reallocated when that changes.
#include "Passes.h"

namespace refraction {

void ensureLayerStorage(GpuState::LayerStorage& layers, glm::ivec2 size, int capacity,
                        int surfaceSlots, bool motions) {
    const std::size_t pixels = std::size_t(size.x) * std::size_t(size.y);
    const std::size_t motionBytes =
        motions ? pixels * std::size_t(capacity) * sizeof(std::uint32_t) : sizeof(std::uint32_t);
    if (layers.motions.size() != motionBytes)
        layers.motions = gl::Buffer(motionBytes);
    const std::size_t layerBytes = 2 * sizeof(std::uint32_t) * pixels;
    const std::size_t surfaceBytes = layerBytes * std::size_t(surfaceSlots);
    if (layers.surfaces.size() != surfaceBytes)
        layers.surfaces = surfaceSlots > 0 ? gl::Buffer(surfaceBytes) : gl::Buffer();
    layers.surfaceSlots = surfaceSlots;
    const std::size_t headBytes =
        (pixels * layerHeadWords(surfaceSlots) + kOverflowListHeader) * sizeof(std::uint32_t);
    if (layers.heads.size() != headBytes)
        layers.heads = gl::Buffer(headBytes);
    if (layers.size == size && layers.capacity == capacity)
        return;
    layers.depths = gl::Buffer(pixels * layerDepthSlots(capacity) * sizeof(float));
    layers.attrs = gl::Buffer(layerBytes * std::size_t(capacity));
    layers.size = size;
    layers.capacity = capacity;
}

std::size_t layerHeadPlanes(int surfaceSlots) {
    // the count, then the fallback's two sides: each its key, and with surfaces its surface
    return 1 + 2 * std::size_t(1 + (surfaceSlots > 0 ? kFallbackSurfaceWords : 0));
}

std::size_t layerHeadWords(int surfaceSlots) {
    return layerHeadPlanes(surfaceSlots) + 1; // and the pixel's place in the overflow list
}

std::size_t overflowListOffset(const GpuState::LayerStorage& layers) {
    const std::size_t pixels = std::size_t(layers.size.x) * std::size_t(layers.size.y);
    return layerHeadPlanes(layers.surfaceSlots) * pixels * sizeof(std::uint32_t);
}

std::size_t layerDepthSlots(int capacity) {
    return (std::size_t(capacity) + 3) / 4 * 4;
}

std::size_t layerBytesPerPixel(int capacity, bool outlines, int surfaceSlots) {
    // The arrays (head, depth slots, attributes, surfaces), the depth maps the resolve pass
    // writes, and the nearest layers' map the outline pass reads.
    const std::size_t layer = 2 * sizeof(std::uint32_t);
    return layerHeadWords(surfaceSlots) * sizeof(std::uint32_t) +
           layerDepthSlots(capacity) * sizeof(float) +
           std::size_t(capacity + surfaceSlots) * layer +
           layerDepthSlots(capacity) * sizeof(float) + (outlines ? sizeof(float) : 0);
}

} // namespace refraction
