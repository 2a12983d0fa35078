// The frame's glass ids, one a character and material, and their optics as the shaders read
// them (GlassMaterialGpu), with the textures the trace reads at its hits.
#include "Passes.h"

#include "model/Optics.h"

#include "engine/core/Log.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

namespace refraction {

namespace {

/** `map` of `item`'s model as a texture the trace reads (among the first
 *  slot::kTracedTextures.count distinct ones of the frame; past them: a warning, and traced
 *  hits go without it). */
TracedTextureGpu tracedTexture(FrameContext& c, const render::DrawItem& item,
                               const scene::TextureRef& map, bool colour) {
    TracedTextureGpu traced;
    const gl::Texture* texture = map.present() ? (colour ? item.materials->srgb(map.texture)
                                                         : item.materials->linear(map.texture))
                                               : nullptr;
    if (!texture)
        return traced;
    auto& textures = c.gpu->tracedTextures;
    auto at = std::find(textures.begin(), textures.end(), texture);
    if (at == textures.end() && textures.size() < slot::kTracedTextures.count)
        at = textures.insert(textures.end(), texture);
    if (at == textures.end()) {
        if (!c.gpu->warnedTracedTextures)
            core::logWarning("refraction: more than " +
                             std::to_string(slot::kTracedTextures.count) +
                             " glass textures in one frame; the trace meets the others' "
                             "surfaces without them");
        c.gpu->warnedTracedTextures = true;
        return traced;
    }
    traced.unit = std::int32_t(at - textures.begin());
    traced.uvSet = map.texCoord;
    traced.row0 = {map.transform[0][0], map.transform[1][0], map.transform[2][0]};
    traced.row1 = {map.transform[0][1], map.transform[1][1], map.transform[2][1]};
    return traced;
}

/** The optics of glass id `item` (its character's glass extent `extent`, solid `solid`). */
GlassMaterialGpu glassMaterial(FrameContext& c, const render::DrawItem& item, double extent,
                               int solid) {
    const scene::Material* m = item.values;
    const Optics o = opticsFor(c.settings, m, item.source->overrides, extent);
    GlassMaterialGpu g{};
    g.ior = o.ior;
    g.transmission = o.transmission;
    g.sigma = o.sigma;
    g.roughness = o.roughness;
    g.baseColor = glm::vec3(o.baseColor);
    g.metallic = o.metallic;
    g.emissive = m ? m->emissiveFactor * m->emissiveStrength : glm::vec3(0.0f);
    g.solid = std::uint32_t(solid);
    g.specularColor = o.specularColor;
    g.specularWeight = o.specularWeight;
    g.sheenColor = o.sheenColor;
    g.sheenRoughness = o.sheenRoughness;
    g.clearcoat = o.clearcoat;
    g.clearcoatRoughness = o.clearcoatRoughness;
    g.iridescence = o.iridescence;
    g.iridescenceIor = o.iridescenceIor;
    g.filmThickness = o.iridescenceThickness;
    g.authored = m && m->isTransmissive() ? 1u : 0u;
    if (!m)
        return g;
    g.normalScale = m->normalTexture.scale;
    g.normalTexture = tracedTexture(c, item, m->normalTexture, false);
    g.baseColorTexture = tracedTexture(c, item, m->baseColorTexture, true);
    if (g.authored) {
        g.metallicRoughnessTexture = tracedTexture(c, item, m->metallicRoughnessTexture, false);
        g.transmissionTexture = tracedTexture(c, item, m->transmissionTexture, false);
    }
    return g;
}

/** Whether glass of material `m` has a transmission or metallic-roughness texture the walk
 *  reads: only a material authored transmissive reads them. */
bool transmissionTextured(const scene::Material* m) {
    return m && m->isTransmissive() &&
           (m->transmissionTexture.present() || m->metallicRoughnessTexture.present());
}

} // namespace

void assignGlassIds(FrameContext& c) {
    const auto& items = c.frame->items;
    c.gpu->glassIds.assign(items.size(), -1);
    c.gpu->glassOptics.clear();
    c.gpu->tracedTextures.clear();
    c.texturedGlass = c.baseColorTexturedGlass = c.transmissionTexturedGlass = false;
    c.normalMappedGlass = false;
    std::map<std::pair<std::uint64_t, int>, int> ids;
    std::map<std::uint64_t, int> solids; // a character's glass is one solid (the media rule)
    bool full = false;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const render::DrawItem& item = items[i];
        if (!c.isGlass(item))
            continue;
        const auto key = std::pair{item.key, item.material};
        if (const auto known = ids.find(key); known != ids.end()) {
            c.gpu->glassIds[i] = known->second;
            continue;
        }
        if (c.gpu->glassOptics.size() == kMaxGlassIds) {
            full = true;
            c.gpu->glassIds[i] = int(kMaxGlassIds) - 1;
            continue;
        }
        const int solid = solids.emplace(item.key, int(solids.size())).first->second;
        c.gpu->glassOptics.push_back(
            glassMaterial(c, item, c.gpu->glassExtent(*item.source), solid));
        const scene::Material* material = item.values;
        c.baseColorTexturedGlass =
            c.baseColorTexturedGlass || (material && material->baseColorTexture.present());
        c.transmissionTexturedGlass = c.transmissionTexturedGlass || transmissionTextured(material);
        c.texturedGlass = c.baseColorTexturedGlass || c.transmissionTexturedGlass;
        c.normalMappedGlass =
            c.normalMappedGlass || (material && material->normalTexture.present());
        ids.emplace(key, int(c.gpu->glassOptics.size()) - 1);
        c.gpu->glassIds[i] = int(c.gpu->glassOptics.size()) - 1;
    }
    if (full && !c.gpu->warnedGlassIds) {
        core::logWarning("refraction: more than 255 glass materials (character x material) in "
                         "one frame; the layered path draws the rest with the 255th's optics");
        c.gpu->warnedGlassIds = true;
    }
}

} // namespace refraction
