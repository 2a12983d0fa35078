// The refraction plugin's storage (buffers, framebuffers) and per-geometry caches, kept across
// frames; its passes' programs come from the engine's program cache. The glass BVH, the glass
// materials and the walk's counters are imported into each frame's graph (importBuffers), and a
// pass reaches them only through the handles it declared. Private to the plugin.
#pragma once

#include "GlassBvh.h"

#include "engine/gl/Buffer.h"
#include "engine/gl/Commands.h"
#include "engine/gl/Framebuffer.h"
#include "engine/gl/Program.h"
#include "engine/render/FrameInfo.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

namespace refraction {

/** A texture the trace reads at its hits, as glass_materials.glsl's TracedTexture. */
struct TracedTextureGpu {
    glm::vec3 row0{1.0f, 0.0f, 0.0f}; ///< the texture transform's first row
    std::int32_t unit = -1;           ///< among slot::kTracedTextures' units; -1: none
    glm::vec3 row1{0.0f, 1.0f, 0.0f};
    std::int32_t uvSet = 0;
};

/** One glass id's optics as glass_materials.glsl's GlassMaterial reads them (std430: each vec3
 *  followed by a scalar, the same fields in the same order; GlLayer checks the offsets). */
struct GlassMaterialGpu {
    glm::vec3 ior; ///< per channel
    float transmission;
    glm::vec3 sigma; ///< absorption per world unit
    float roughness;
    glm::vec3 baseColor;
    float metallic;
    glm::vec3 emissive;
    std::uint32_t solid; ///< the character's index among the glass ones
    glm::vec3 specularColor;
    float specularWeight;
    glm::vec3 sheenColor;
    float sheenRoughness;
    float clearcoat, clearcoatRoughness;
    float iridescence, iridescenceIor;
    float filmThickness;
    float normalScale = 1.0f;
    std::uint32_t authored; ///< glass by its own transmission
    std::uint32_t spare = 0;
    TracedTextureGpu normalTexture, baseColorTexture, metallicRoughnessTexture, transmissionTexture;
};
static_assert(sizeof(GlassMaterialGpu) == 16 * 16);

// Three small buffers, one a job, each as its GLSL block reads it (std430; SharedLayout checks
// the offsets).

/** The glass's extent on screen and in view space (refraction/passes/glass_extent.glsl): written by
 *  the glass_extent pass, read by every pass over the glass rectangle and by the walk. */
struct GlassExtentGpu {
    std::int32_t pixelMin[2], pixelMax[2]; ///< inclusive; empty while min > max
    std::int32_t boxMin[3], boxMax[3];     ///< view space, floats as ordered ints
};

/** The depth ranges of the pair's surfaces (refraction/passes/pair_ranges.glsl, positive floats'
 *  bits): written by the pair's resolve, read by the papers' search. */
struct PairRangesGpu {
    std::uint32_t backRange[2], frontMin;
};

/** What the walk and the hybrid's trace count (refraction/passes/walk_counters.glsl), read back as
 *  LayerStats. */
struct WalkCountersGpu {
    std::uint32_t overflowPixels;                          ///< pixels over K in the walk
    std::uint32_t traceRays, traceSteps[2], traceMaxSteps; ///< the trace's
    std::uint32_t walkedPixels, hybridTraced, hybridBy[4]; ///< the hybrid's
    std::uint32_t freshPixels, freshGroups[3];             ///< take the fresh samples; their groups
};

/** What a frame's layer arrays (layers.glsl; the frame graph lends them: passes/Passes.h's
 *  LayerBuffers) are made for: its size, K, surfaces a pixel (with textured glass) and each
 *  layer's motion (where it accumulates). */
struct LayerShape {
    glm::ivec2 size{0};
    int capacity = 0, surfaceSlots = 0;
    bool motions = false;
    std::size_t pixels() const { return std::size_t(size.x) * std::size_t(size.y); }
};

struct GpuState {
    /** What the last layered frame's arrays were made for (layerStats). */
    LayerShape layers;
    gl::Buffer glassMaterials; // GlassMaterial (layers.glsl) per glass id, grown as needed
    /** This frame's glass ids per frame item (-1: not glass) and optics per id (one per
     *  character and material), refilled each frame in place (assignGlassIds). */
    std::vector<int> glassIds;
    std::vector<GlassMaterialGpu> glassOptics;
    bool warnedGlassIds = false; // the 256-id limit was reported
    /** Each model's sides at rest (restSides, for glassExtent), kept while the model lives. */
    std::map<const scene::Model*, std::pair<std::weak_ptr<const scene::Model>, glm::vec3>> sides;
    /** A character's glass extent (Optics.h's glassExtent), its model's sides measured once. */
    double glassExtent(const scene::Character& character);
    /** The glass textures the trace reads at its hits (trace.glsl's uTracedTextures), this
     *  frame: normal maps, base colours, metallic-roughness and transmission. */
    std::vector<const gl::Texture*> tracedTextures;
    bool warnedTracedTextures = false; // more than slot::kTracedTextures.count was reported
    gl::Framebuffer framebuffer;
    /** The scene's colour, read to convert it into the walk's single-precision target. */
    gl::Framebuffer sceneColorRead;
    gl::VertexArray emptyVao;
    gl::Buffer counters{sizeof(WalkCountersGpu)};
    /** The BVH over the frame's glass as drawn, and for the tracing methods its opaque parts
     *  too (parts: its draw items' (character, instance, primitive), in frame order), rebuilt
     *  from scratch when the parts change. */
    struct Glass {
        using Part = std::tuple<std::uint64_t, std::uint32_t, std::uint32_t>;
        std::vector<Part> parts;
        std::unique_ptr<GlassBvh> bvh;
        /** The frame's items in the BVH, their parts and tags (GlassBvh::setTags; refilled in
         *  place). */
        std::tuple<std::vector<const render::DrawItem*>, std::vector<Part>,
                   std::vector<std::uint32_t>>
            frame;
        /** Part `part`'s index in `parts`, or -1. */
        int find(const Part& part) const;
    } glass;
};

} // namespace refraction
