// Private to the plugin: its entries in the registry of numbers C++ and GLSL share
// (engine/gl/Registry.h), which RefractionPlugin::initialize registers as "refraction". The
// shaders read each as a define; C++ binds through the slots below. Storage bindings from
// gl::slot::kFirstPluginBinding; texture units from 24 (the engine's end below).
#pragma once

#include "engine/gl/Registry.h"

#include <cstdint>
#include <span>

namespace refraction::slot {

using gl::StorageSlot;
using gl::TextureSlot;

// Storage: what the passes read through the frame (each binds it before its draws).
inline constexpr StorageSlot kNormalDistances{20, "NORMAL_DISTANCES_BINDING", "NormalDistances"};
inline constexpr StorageSlot kGlassExtent{21, "GLASS_EXTENT_BINDING", "GlassExtent"};
inline constexpr StorageSlot kLayerHeads{22, "LAYER_HEADS_BINDING", "LayerHeads"};
inline constexpr StorageSlot kLayerDepths{23, "LAYER_DEPTHS_BINDING", "LayerDepths"};
inline constexpr StorageSlot kLayerAttrs{24, "LAYER_ATTRS_BINDING", "LayerAttrs"};
inline constexpr StorageSlot kGlassMaterials{25, "GLASS_MATERIALS_BINDING", "GlassMaterials"};
inline constexpr StorageSlot kHandedOver{26, "HANDED_OVER_BINDING", "HandedOver"};
// The glass BVH (bvh.glsl, GlassBvh): what a traversal reads, then the build's own.
inline constexpr StorageSlot kWorldMesh{27, "WORLD_MESH_BINDING", "WorldMesh"};
inline constexpr StorageSlot kWorldIndices{28, "WORLD_INDICES_BINDING", "WorldIndices"};
inline constexpr StorageSlot kBvhNodes{29, "BVH_NODES_BINDING", "BvhNodes"};
inline constexpr StorageSlot kBvhOrder{30, "BVH_ORDER_BINDING", "BvhOrder"};
inline constexpr StorageSlot kBvhBoxes{31, "BVH_BOXES_BINDING", "BvhBoxes"};
inline constexpr StorageSlot kBvhLeafCorners{32, "BVH_LEAF_CORNERS_BINDING", "BvhLeafCorners"};
inline constexpr StorageSlot kBvhTags{33, "BVH_TAGS_BINDING", "BvhTags"};
inline constexpr StorageSlot kBvhPackedBoxes{34, "BVH_PACKED_BOXES_BINDING", "BvhPackedBoxes"};
inline constexpr StorageSlot kWorldUvs{35, "WORLD_UVS_BINDING", "WorldUvs"};
inline constexpr StorageSlot kBvhBuild{36, "BVH_BUILD_BINDING", "BvhBuild"};
inline constexpr StorageSlot kBvhKeys{37, "BVH_KEYS_BINDING", "BvhKeys"};
inline constexpr StorageSlot kBvhParents{38, "BVH_PARENTS_BINDING", "BvhParents"};
inline constexpr StorageSlot kBvhVisits{39, "BVH_VISITS_BINDING", "BvhVisits"};
inline constexpr StorageSlot kLayerSurfaces{40, "LAYER_SURFACES_BINDING", "LayerSurfaces"};
inline constexpr StorageSlot kLayerMotions{41, "LAYER_MOTIONS_BINDING", "LayerMotions"};
inline constexpr StorageSlot kPairRanges{42, "PAIR_RANGES_BINDING", "PairRanges"};
inline constexpr StorageSlot kWalkCounters{43, "WALK_COUNTERS_BINDING", "WalkCounters"};
/** The caustics (caustics.glsl): the light's texels whose rays meet glass, listed by the glass
 *  shadow pass, and the photons' light added up per texel of the caustics atlas. */
inline constexpr StorageSlot kCausticEmitters{44, "CAUSTIC_EMITTERS_BINDING", "CausticEmitters"};
inline constexpr StorageSlot kCausticSums{45, "CAUSTIC_SUMS_BINDING", "CausticSums"};

// Texture units.
inline constexpr TextureSlot kSceneColor{26, "SCENE_COLOR_UNIT"};
inline constexpr TextureSlot kSceneDepth{27, "SCENE_DEPTH_UNIT"};
inline constexpr TextureSlot kLayerDepthMaps{28, "LAYER_DEPTH_MAPS_UNIT", 2}; ///< layers 0-3, 4-7
inline constexpr TextureSlot kPairNormals{30, "PAIR_NORMALS_UNIT", 2};        ///< front, back
/** The pair capture's maps the resolve reads (pair_resolve.frag.glsl): the one pass's nearest and
 *  farthest targets, or the two passes' front depth, front normal, back depth, back normal. */
inline constexpr TextureSlot kPairMaps{32, "PAIR_MAPS_UNIT", 4};
inline constexpr TextureSlot kOutlineSurface{36,
                                             "OUTLINE_SURFACE_UNIT"}; ///< the walk's nearest layers
/** The glass textures the trace reads at its hits (trace.glsl): normal maps, then base colour,
 *  transmission and roughness (GpuState::tracedTextures). */
inline constexpr TextureSlot kTracedTextures{37, "TRACED_TEXTURES_UNIT", 8};
/** The two passes' surfaces where the frame's glass is textured (pair_resolve.frag.glsl): the
 *  front's, the back's. */
inline constexpr TextureSlot kPairSurfaces{45, "PAIR_SURFACES_UNIT", 2};
/** The engine's shadow depth atlas read as depths (not compared): where photons land, and the
 *  receivers the caustics are for. */
inline constexpr TextureSlot kCausticDepth{47, "CAUSTIC_DEPTH_UNIT"};
/** The opaque scene's nearest depth over tiles, a mip chain (scene_depth_tiles.comp.glsl): what
 *  the marches through the nearby scene test first (march.glsl, segmentInFront). */
inline constexpr TextureSlot kSceneDepthTiles{48, "SCENE_DEPTH_TILES_UNIT"};

} // namespace refraction::slot

namespace refraction {

/** Bits of a traced triangle's tag (GlassBvh::setTags): an opaque part's, and one with a base
 *  colour texture (the rest: the opaque material's factors); a glass part's its glass id, and
 *  this bit where its placement mirrors it (its winding reversed: DrawItem::mirrored). */
inline constexpr std::uint32_t kOpaqueTag = 0x80000000u, kOpaqueTextured = 0x40000000u,
                               kMirroredTag = 0x20000000u;
/** A layer's attributes (layers.glsl): bits 0-7 its glass id, this bit front-facing. */
inline constexpr std::uint32_t kLayerFront = 256u;
/** Words of the overflow fallback's surface in the layer heads, a side (layers.glsl,
 *  bidForFallback: packSurface's 48 bits, 16 a word), after its key; with textured glass. */
inline constexpr int kFallbackSurfaceWords = 3;
/** A depth slot with no layer, a pixel without the opaque scene (the depth maps' clear value);
 *  a depth from kUnusedDepth up marks one. The pair's MAX-blended targets clear to
 *  kNoSurface (below any fragment). */
inline constexpr float kNoDepth = 3.0e38f, kUnusedDepth = 1.0e38f, kNoSurface = -3.0e38f;
/** The caustics atlas is the shadow atlases' size divided by this (its tiles theirs, scaled). */
inline constexpr int kCausticScale = 4;
/** The caustics' coarse cells are this many fine cells wide (caustics.glsl). */
inline constexpr int kCausticCoarse = 4;
/** The photons' light is added up in fixed point (caustics.glsl): this many units are 1, the
 *  light that reaches a receiver unblocked. */
inline constexpr double kCausticFixed = 1048576.0;
/** Glass ids a layer can name (8 bits, less the walk's 0 for air). */
inline constexpr std::size_t kMaxGlassIds = 255;

/** The plugin's table: the slots above, the tags and bits, and every enum parameter's choices
 *  as <PARAMETER>_<CHOICE> (METHOD_DIR, DEBUG_BACK_DEPTH: their indices, Settings' enums), the
 *  hybrid's criteria (Settings::HybridCriterion). */
std::span<const gl::Shared> sharedTable();

} // namespace refraction
