// The registry of numbers C++ and GLSL share: storage-buffer bindings, image and texture units,
// enum values, bit layouts and sentinels. Each owner (the engine here, a plugin in its own
// table) declares its numbers once as typed constants and lists them in a table; the shader
// library prepends every registered table to every shader as #defines, so no shader spells a
// binding or an enum value as a literal, and registering a table that reuses another's binding
// or name fails. In debug and test builds every draw and dispatch checks the program's storage
// blocks against the registry and the buffers bound (checkProgramBindings).
//
// Storage bindings are one space for the whole frame:
//   0-15   pass-local: bound by a pass right before its draws or dispatches (OpenSubdiv's GL
//          evaluator binds 0-15 itself, so nothing bound there outlives its pass);
//   16-19  the engine's frame-wide bindings (the lights, bound once a frame);
//   20-    plugins (kFirstPluginBinding), each binding what it reads before its passes use it.
// Texture units: 0-25 the engine's, 26- the plugins'. Image units: the engine's 0-1.
#pragma once

#include "engine/core/Result.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace gl {

/** A storage-buffer binding: its index, the GLSL define naming it and the GLSL block that must
 *  sit there (the check compares the program's block names with it). */
struct StorageSlot {
    std::uint32_t index;
    const char* define;
    const char* block;
};

/** An image unit (imageLoad/imageStore targets). */
struct ImageSlot {
    std::uint32_t index;
    const char* define;
};

/** A run of `count` texture units from `index` (a sampler array takes one unit an element). */
struct TextureSlot {
    std::uint32_t index;
    const char* define;
    std::uint32_t count = 1;
};

/** One entry of a registry table: a slot or a plain constant, as GLSL reads it. */
struct Shared {
    enum class Kind : std::uint8_t { Storage, Image, Texture, Int, Uint, Float };
    Kind kind;
    const char* define;
    double value;            ///< the index for slots
    const char* block = "";  ///< Storage: the GLSL block
    std::uint32_t count = 1; ///< Texture: units in the run

    constexpr Shared(const StorageSlot& s)
        : kind(Kind::Storage), define(s.define), value(s.index), block(s.block) {}
    constexpr Shared(const ImageSlot& s) : kind(Kind::Image), define(s.define), value(s.index) {}
    constexpr Shared(const TextureSlot& s)
        : kind(Kind::Texture), define(s.define), value(s.index), count(s.count) {}
    constexpr Shared(Kind k, const char* name, double v) : kind(k), define(name), value(v) {}

    /** An int constant (an enum's value), an unsigned one (a bit or a mask) or a float one. */
    static constexpr Shared integer(const char* name, std::int64_t v) {
        return {Kind::Int, name, double(v)};
    }
    static constexpr Shared bits(const char* name, std::uint32_t v) {
        return {Kind::Uint, name, double(v)};
    }
    static constexpr Shared real(const char* name, double v) { return {Kind::Float, name, v}; }

    /** `#define NAME VALUE` without the directive: "NAME VALUE". */
    std::string glsl() const;
};

/** Whether no two slots of one kind in `table` overlap and no define repeats: a table states
 *  `static_assert(gl::distinct(kTable))` beside itself. */
constexpr bool distinct(std::span<const Shared> table) {
    auto same = [](const char* a, const char* b) {
        for (; *a && *a == *b; ++a, ++b) {
        }
        return *a == *b;
    };
    for (std::size_t i = 0; i < table.size(); ++i)
        for (std::size_t j = i + 1; j < table.size(); ++j) {
            const Shared &a = table[i], &b = table[j];
            if (same(a.define, b.define))
                return false;
            const bool slots = a.kind == b.kind &&
                               (a.kind == Shared::Kind::Storage || a.kind == Shared::Kind::Image ||
                                a.kind == Shared::Kind::Texture);
            if (slots && a.value < b.value + b.count && b.value < a.value + a.count)
                return false;
        }
    return true;
}

/** The tables registered so far (the engine's first), checked against each other. */
class Registry {
public:
    Registry();
    /** Adds `owner`'s table (again: nothing, where the owner registered the same numbers).
     *  Fails, naming both entries, where a define is registered already or a slot overlaps one
     *  of another owner's (nothing is added then). */
    core::Status add(const std::string& owner, std::span<const Shared> table);
    /** Every entry as a GLSL define body ("NAME VALUE"), in registration order. */
    std::vector<std::string> defines() const;
    /** The highest storage binding registered. */
    std::uint32_t highestStorage() const;

private:
    /** An entry, its names copied (a plugin module's constants may be unloaded first). */
    struct Entry {
        std::string owner, define;
        Shared::Kind kind;
        double value;
        std::uint32_t count;
        Shared shared() const;
    };
    std::vector<Entry> mEntries;
};

/** The engine's slots and constants (the first table of every Registry). */
namespace slot {
// Pass-local storage (0-15).
/// a draw item's deformed vertices (common/vertex.glsl)
inline constexpr StorageSlot kVertices{0, "VERTICES_BINDING", "Vertices"};
inline constexpr StorageSlot kUvs{1, "UVS_BINDING", "Uvs"}; ///< its TEXCOORD_0 in xy, _1 in zw
inline constexpr StorageSlot kIndices{2, "INDICES_BINDING", "Indices"}; ///< its triangles
inline constexpr StorageSlot kRest{3, "REST_BINDING", "Rest"}; ///< deform: the rest vertices
inline constexpr StorageSlot kInfluences{4, "INFLUENCES_BINDING", "Influences"};
inline constexpr StorageSlot kMorphDeltas{5, "MORPH_DELTAS_BINDING", "MorphDeltas"};
inline constexpr StorageSlot kMorphWeights{6, "MORPH_WEIGHTS_BINDING", "MorphWeights"};
inline constexpr StorageSlot kSkinMatrices{7, "SKIN_MATRICES_BINDING", "SkinMatrices"};
inline constexpr StorageSlot kCorners{8, "CORNERS_BINDING", "Corners"}; ///< subdivision's pack
inline constexpr StorageSlot kLimit{9, "LIMIT_BINDING", "Limit"};
inline constexpr StorageSlot kLimitDu{10, "LIMIT_DU_BINDING", "LimitDu"};
inline constexpr StorageSlot kLimitDv{11, "LIMIT_DV_BINDING", "LimitDv"};
inline constexpr StorageSlot kRefinedTangents{12, "REFINED_TANGENTS_BINDING", "RefinedTangents"};
/// a draw item's deformed vertices as the previous frame left them (motion vectors)
inline constexpr StorageSlot kPreviousVertices{13, "PREVIOUS_VERTICES_BINDING", "PreviousVertices"};
// Frame-wide storage (16-19).
inline constexpr StorageSlot kLighting{16, "LIGHTING_BINDING", "Lighting"}; ///< render::Lighting
/** The first storage binding a plugin may register. */
inline constexpr std::uint32_t kFirstPluginBinding = 20;

/** The image a compute pass writes (prefiltering, a plugin's shading dispatch). */
inline constexpr ImageSlot kOutputImage{0, "OUTPUT_IMAGE_UNIT"};
/** The frame's motion (common/motion.glsl) where a plugin writes its own pixels'. */
inline constexpr ImageSlot kMotionImage{1, "MOTION_IMAGE_UNIT"};

// Texture units, bound by each pass that samples them.
inline constexpr TextureSlot kEnvironment{0, "ENVIRONMENT_UNIT", 2}; ///< prefiltered, irradiance
/// a pass's input image (tonemap, prefilter)
inline constexpr TextureSlot kSource{2, "SOURCE_UNIT"};
inline constexpr TextureSlot kMaterial{3, "MATERIAL_UNIT", 17}; ///< a material's texture slots
/// the frame's motion (common/motion.glsl): the temporal resolve's, and a plugin's to read
inline constexpr TextureSlot kMotion{20, "MOTION_UNIT"};
/// the temporal history: the last resolved colour and the motion texels it was resolved with
inline constexpr TextureSlot kHistory{21, "HISTORY_UNIT", 2};
/// the frame's shadow atlases (common/shadows.glsl): the casters' depth, compared, the glass's,
/// and the caustics the glass focuses onto the receivers
inline constexpr TextureSlot kShadowDepth{23, "SHADOW_DEPTH_UNIT"};
inline constexpr TextureSlot kShadowGlass{24, "SHADOW_GLASS_UNIT"};
inline constexpr TextureSlot kShadowCaustics{25, "SHADOW_CAUSTICS_UNIT"};

/** The engine's table: every slot above. */
inline constexpr Shared kEngineTable[] = {kVertices,        kUvs,
                                          kIndices,         kRest,
                                          kInfluences,      kMorphDeltas,
                                          kMorphWeights,    kSkinMatrices,
                                          kCorners,         kLimit,
                                          kLimitDu,         kLimitDv,
                                          kRefinedTangents, kPreviousVertices,
                                          kLighting,        kOutputImage,
                                          kMotionImage,     kEnvironment,
                                          kSource,          kMaterial,
                                          kMotion,          kHistory,
                                          kShadowDepth,     kShadowGlass,
                                          kShadowCaustics};
static_assert(distinct(kEngineTable));
} // namespace slot

} // namespace gl
