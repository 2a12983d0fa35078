// The layer arrays (layers.glsl) as the frame graph lends them, and their sizes: what they hold
// a pixel.
#include "Passes.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace refraction {

LayerBuffers createLayers(fg::Builder& b, const LayerShape& shape) {
    const std::size_t pixels = shape.pixels(), word = sizeof(std::uint32_t);
    const std::size_t layer = 2 * word * pixels; // a uvec2 a pixel
    const auto create = [&](const char* name, std::size_t bytes) {
        return b.write(b.create(std::string("refraction.layers.") + name, gl::BufferDesc{bytes}));
    };
    LayerBuffers layers;
    layers.shape = shape;
    layers.heads =
        create("heads", (pixels * layerHeadWords(shape.surfaceSlots) + kOverflowListHeader) * word);
    layers.depths = create("depths", pixels * layerDepthSlots(shape.capacity) * sizeof(float));
    layers.attrs = create("attrs", layer * std::size_t(shape.capacity));
    if (shape.surfaceSlots > 0)
        layers.surfaces = create("surfaces", layer * std::size_t(shape.surfaceSlots));
    layers.motions =
        create("motions", shape.motions ? pixels * std::size_t(shape.capacity) * word : word);
    return layers;
}

namespace {

/** `layers`, each array's handle the one `declare` (a read or a write) returns for it. */
template <class Declare> LayerBuffers declared(LayerBuffers layers, Declare declare) {
    for (fg::BufferHandle* h :
         {&layers.heads, &layers.depths, &layers.attrs, &layers.surfaces, &layers.motions})
        if (h->valid())
            *h = declare(*h);
    return layers;
}

} // namespace

LayerBuffers writeLayers(fg::Builder& b, const LayerBuffers& layers) {
    return declared(layers, [&b](fg::BufferHandle h) { return b.write(h); });
}

LayerBuffers readLayers(fg::Builder& b, const LayerBuffers& layers) {
    return declared(layers, [&b](fg::BufferHandle h) { return b.read(h); });
}

std::size_t layerHeadPlanes(int surfaceSlots) {
    // the count, then the fallback's two sides: each its key, and with surfaces its surface
    return 1 + 2 * std::size_t(1 + (surfaceSlots > 0 ? kFallbackSurfaceWords : 0));
}

std::size_t layerHeadWords(int surfaceSlots) {
    return layerHeadPlanes(surfaceSlots) + 1; // and the pixel's place in the overflow list
}

std::size_t overflowListOffset(const LayerShape& shape) {
    return layerHeadPlanes(shape.surfaceSlots) * shape.pixels() * sizeof(std::uint32_t);
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
