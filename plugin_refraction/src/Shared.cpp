// The plugin's table of shared numbers: its slots and bits, and the choices of its enum
// parameters named from the parameter table itself (one list of names for C++ and GLSL).
#include "Shared.h"

#include "Settings.h"
#include "model/GlassModel.h"

#include <cctype>
#include <deque>
#include <string>
#include <vector>

namespace refraction {

namespace {

using gl::Shared;

constexpr Shared kFixed[] = {
    slot::kNormalDistances,
    slot::kGlassExtent,
    slot::kLayerHeads,
    slot::kLayerDepths,
    slot::kLayerAttrs,
    slot::kGlassMaterials,
    slot::kHandedOver,
    slot::kWorldMesh,
    slot::kWorldIndices,
    slot::kBvhNodes,
    slot::kBvhOrder,
    slot::kBvhBoxes,
    slot::kBvhLeafCorners,
    slot::kBvhTags,
    slot::kBvhPackedBoxes,
    slot::kWorldUvs,
    slot::kBvhBuild,
    slot::kBvhKeys,
    slot::kBvhParents,
    slot::kBvhVisits,
    slot::kLayerSurfaces,
    slot::kLayerMotions,
    slot::kPairRanges,
    slot::kWalkCounters,
    slot::kSceneColor,
    slot::kSceneDepth,
    slot::kLayerDepthMaps,
    slot::kPairNormals,
    slot::kPairMaps,
    slot::kOutlineSurface,
    slot::kTracedTextures,
    slot::kPairSurfaces,
    slot::kCausticEmitters,
    slot::kCausticSums,
    slot::kCausticDepth,
    slot::kSceneDepthTiles,
    Shared::bits("OPAQUE_TAG", kOpaqueTag),
    Shared::bits("OPAQUE_TEXTURED_TAG", kOpaqueTextured),
    Shared::bits("MIRRORED_TAG", kMirroredTag),
    Shared::bits("LAYER_FRONT_BIT", kLayerFront),
    Shared::integer("FALLBACK_SURFACE_WORDS", kFallbackSurfaceWords),
    Shared::real("NO_DEPTH", kNoDepth),
    Shared::real("UNUSED_DEPTH", kUnusedDepth),
    Shared::real("NO_SURFACE", kNoSurface),
    Shared::integer("HYBRID_OVERFLOW", Settings::kHandOverflow),
    Shared::integer("HYBRID_LEFT_LAYERS", Settings::kHandOffLayers),
    Shared::integer("HYBRID_REFLECTION", Settings::kHandReflection),
    Shared::integer("HYBRID_OUTLINE", Settings::kHandOutline),
    Shared::integer("DISPERSION_NONE", Settings::kNoDispersion),
    Shared::integer("MAX_MEDIA", model::kMaxMedia),
    Shared::integer("TRACED_TEXTURES", slot::kTracedTextures.count),
    Shared::integer("SPLIT_DEPTH", model::kSplitDepth),
    Shared::real("SPLIT_WEIGHT", model::kSplitWeight),
    Shared::real("SMOOTH_ROUGHNESS", model::kSmooth),
    Shared::integer("MAX_PHOTON_CROSSINGS", model::kMaxPhotonCrossings),
    Shared::integer("CAUSTIC_SCALE", kCausticScale),
    Shared::integer("CAUSTIC_COARSE", kCausticCoarse),
    Shared::real("CAUSTIC_FIXED", kCausticFixed),
};
static_assert(gl::distinct(kFixed));

/** "per-channel" -> "PER_CHANNEL". */
std::string upper(const std::string& name) {
    std::string out;
    for (const char c : name)
        out += std::isalnum(static_cast<unsigned char>(c))
                   ? char(std::toupper(static_cast<unsigned char>(c)))
                   : '_';
    return out;
}

} // namespace

std::span<const gl::Shared> sharedTable() {
    static const auto table = [] {
        // The choices' names outlive the table (a deque keeps them in place).
        static std::deque<std::string> names;
        std::vector<Shared> entries(std::begin(kFixed), std::end(kFixed));
        for (const plugin::Parameter& p : Settings::parameterTable()) {
            if (p.type != plugin::Parameter::Type::Enum)
                continue;
            for (std::size_t i = 0; i < p.choices.size(); ++i) {
                names.push_back(upper(p.name) + "_" + upper(p.choices[i]));
                entries.push_back(Shared::integer(names.back().c_str(), std::int64_t(i)));
            }
        }
        return entries;
    }();
    return table;
}

} // namespace refraction
