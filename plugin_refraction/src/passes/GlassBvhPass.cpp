// `refraction.glass_bvh` (ISR, trace, hybrid, caustics): every glass part's deformed surface as
// drawn (refined under subdivision; for the tracing methods and the caustics every opaque
// part's too) gathered into the world mesh, the glass BVH refitted (or rebuilt) and its
// triangles' tags; for ISR d_N cast from every vertex (GlassBvh).
#include "Passes.h"

#include "engine/deform/GpuDeformer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace refraction {

namespace {

/** An opaque part's tag (kOpaqueTag): its material's factors, for a traced ray that
 *  meets it (trace.glsl's opaqueSeen). */
std::uint32_t opaqueTag(const render::DrawItem& item) {
    glm::vec3 base(1.0f);
    float metallic = 1.0f, roughness = 1.0f; // glTF's default material
    bool textured = false;
    if (item.values) {
        const scene::Material& m = *item.values;
        base = glm::vec3(m.baseColorFactor);
        metallic = m.metallicFactor;
        roughness = m.roughnessFactor;
        textured = m.baseColorTexture.present();
    }
    const glm::uvec3 colour(glm::round(glm::sqrt(glm::clamp(base, 0.0f, 1.0f)) * 127.0f));
    const auto bits = [](float v, float levels) {
        return std::uint32_t(std::round(std::clamp(v, 0.0f, 1.0f) * levels));
    };
    return kOpaqueTag | (textured ? kOpaqueTextured : 0u) | colour.r | colour.g << 7 |
           colour.b << 14 | bits(roughness, 31.0f) << 21 | bits(metallic, 15.0f) << 26;
}

} // namespace

void addGlassBvhPass(fg::FrameGraph& graph, const FrameContext& c, FrameBuffers& buffers) {
    struct Data {
        fg::BufferHandle bvh;
    };
    const Data& pass = graph.addPass<Data>(
        "refraction.glass_bvh",
        [&](fg::Builder& b, Data& d) {
            b.read(buffers.vertices);
            d.bvh = b.write(buffers.bvh);
        },
        [c](const fg::Resources& r, const Data& d, gl::Context&) -> core::Status {
            auto programs = BvhPrograms::from(*c.frame->programs);
            if (!programs)
                return core::Error{"refraction: " + programs.error().message};
            GpuState& gpu = *c.gpu;
            GpuState::Glass& glass = glassBvh(r, d.bvh);
            // This frame's parts: its glass items and, for the trace and the caustics, its
            // opaque ones (an exit ray or a photon meets them exactly), with their tags, in
            // storage kept across frames.
            auto& [items, parts, tags] = glass.frame;
            items.clear();
            parts.clear();
            tags.clear();
            const bool opaque = c.bvhHoldsOpaque();
            for (std::size_t index = 0; index < c.frame->items.size(); ++index) {
                const render::DrawItem& item = c.frame->items[index];
                if (!c.isGlass(item) && !opaque)
                    continue;
                items.push_back(&item);
                parts.emplace_back(item.key, item.instance, item.primitiveIndex);
                tags.push_back(c.isGlass(item) ? std::uint32_t(std::max(gpu.glassIds[index], 0)) |
                                                     (item.mirrored ? kMirroredTag : 0u)
                                               : opaqueTag(item));
            }
            if (!glass.bvh || parts != glass.parts) { // new, or other glass parts
                std::vector<const scene::Primitive*> primitives;
                for (const render::DrawItem* item : items)
                    primitives.push_back(item->gpu->topology);
                glass.parts = parts;
                glass.bvh = std::make_unique<GlassBvh>(primitives);
            }
            for (std::size_t i = 0; i < items.size(); ++i)
                glass.bvh->gather(i, *items[i]->gpu->deformed, items[i]->gpu->vertexCount,
                                  items[i]->world, *programs);
            glass.bvh->update(*programs);
            glass.bvh->setTags(tags);
            if (c.settings.usesNormalDistance())
                glass.bvh->castNormalDistances(*programs);
            return core::Status{};
        });
    buffers.bvh = pass.bvh;
}

} // namespace refraction
