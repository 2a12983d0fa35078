// `refraction.glass_bvh` (ISR, trace): every glass part's deformed cage gathered into the world
// cage, the glass BVH refitted (or rebuilt) and its triangles' glass ids; for ISR d_N cast from
// every vertex (GlassBvh).
#include "Passes.h"

#include "engine/deform/GpuDeformer.h"

#include <vector>

namespace refraction {

void addGlassBvhPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers) {
    struct Data {
        fg::BufferHandle distances;
    };
    const Data& pass = graph.addPass<Data>(
        "refraction.glass_bvh",
        [&](fg::Builder& b, Data& d) {
            b.read(buffers.vertices);
            d.distances = b.write(buffers.distances);
        },
        [c](const fg::Resources&, const Data&, gl::Context&) {
            GpuState& gpu = *c.gpu;
            GpuState::Glass& glass = gpu.glass;
            // This frame's glass items, parts and glass ids, in storage kept across frames.
            auto& [items, parts, glassIds] = glass.frame;
            items.clear();
            parts.clear();
            glassIds.clear();
            for (std::size_t index = 0; index < c.frame->items.size(); ++index)
                if (const render::DrawItem& item = c.frame->items[index]; c.isGlass(item)) {
                    items.push_back(&item);
                    parts.emplace_back(item.key, item.instance, item.primitiveIndex);
                    glassIds.push_back(gpu.glassIds[index]);
                }
            if (!glass.bvh || parts != glass.parts) { // new, or other glass parts
                std::vector<const scene::Primitive*> primitives;
                for (const render::DrawItem* item : items)
                    primitives.push_back(item->primitive);
                glass.parts = parts;
                glass.bvh = std::make_unique<GlassBvh>(primitives);
                glass.drawn.clear();
            }
            for (std::size_t i = 0; i < items.size(); ++i) {
                const render::DrawItem& item = *items[i];
                glass.bvh->gather(i, item.geometry->cage(item.instance, item.primitiveIndex).vertices,
                                  std::uint32_t(item.primitive->vertexCount()), item.world,
                                  gpu.bvh);
            }
            glass.bvh->update(gpu.bvh);
            glass.bvh->setGlassIds(glassIds);
            if (!c.settings.usesNormalDistance())
                return;
            glass.bvh->castNormalDistances(gpu.bvh);
            for (std::size_t i = 0; i < items.size(); ++i) {
                const render::DrawItem& item = *items[i];
                if (item.geometry->subdivisionLevel() == 0)
                    continue;
                gl::Buffer& drawn = glass.drawn[parts[i]];
                if (!drawn)
                    drawn = gl::Buffer(std::size_t(item.gpu->vertexCount) * sizeof(float));
                item.geometry->refineScalar(item.instance, item.primitiveIndex,
                                            glass.bvh->distances(), drawn, glass.bvh->base(i));
            }
        });
    buffers.distances = pass.distances;
}

} // namespace refraction
