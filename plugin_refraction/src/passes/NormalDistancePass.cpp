// `refraction.normal_distance` (ISR): per character, its glass parts' deformed cages gathered
// into one world-space cage, the BVH refit, d_N cast from every vertex (NormalDistance).
#include "Passes.h"

#include "engine/deform/GpuDeformer.h"

#include <map>
#include <vector>

namespace refraction {

void addNormalDistancePass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers) {
    struct Data {
        fg::BufferHandle distances;
    };
    const Data& pass = graph.addPass<Data>(
        "refraction.normal_distance",
        [&](fg::Builder& b, Data& d) {
            b.read(buffers.vertices);
            d.distances = b.write(buffers.distances);
        },
        [c](const fg::Resources&, const Data&, gl::Context&) {
            // The glass items of each character, in frame order: its parts.
            std::map<std::uint64_t, std::vector<const render::DrawItem*>> characters;
            for (const render::DrawItem& item : c.frame->items)
                if (c.isGlass(item))
                    characters[item.key].push_back(&item);
            GpuState& gpu = *c.gpu;
            for (const auto& [key, items] : characters) {
                GpuState::Distance& distance = gpu.distances[key];
                std::vector<GpuState::Distance::Part> parts;
                for (const render::DrawItem* item : items)
                    parts.emplace_back(item->instance, item->primitiveIndex);
                if (!distance.cage || parts != distance.parts) { // new, or other glass parts
                    std::vector<const scene::Primitive*> primitives;
                    for (const render::DrawItem* item : items)
                        primitives.push_back(item->primitive);
                    distance.parts = parts;
                    distance.cage = std::make_unique<NormalDistance>(primitives);
                    distance.drawn.clear();
                }
                for (std::size_t i = 0; i < items.size(); ++i) {
                    const render::DrawItem& item = *items[i];
                    distance.cage->gather(
                        i, item.geometry->cage(item.instance, item.primitiveIndex).vertices,
                        std::uint32_t(item.primitive->vertexCount()), item.world, gpu.cageGather);
                }
                distance.cage->update(gpu.refit, gpu.normalDistance);
                for (std::size_t i = 0; i < items.size(); ++i) {
                    const render::DrawItem& item = *items[i];
                    if (item.geometry->subdivisionLevel() == 0)
                        continue;
                    gl::Buffer& drawn = distance.drawn[parts[i]];
                    if (!drawn)
                        drawn = gl::Buffer(std::size_t(item.gpu->vertexCount) * sizeof(float));
                    item.geometry->refineScalar(item.instance, item.primitiveIndex,
                                                distance.cage->distances(), drawn,
                                                distance.cage->base(i));
                }
            }
        });
    buffers.distances = pass.distances;
}

} // namespace refraction
