// The refraction plugin's GL objects and per-geometry caches, kept across frames. Private to
// the plugin.
#pragma once

#include "GlassBvh.h"

#include "engine/gl/Buffer.h"
#include "engine/gl/Commands.h"
#include "engine/gl/Framebuffer.h"
#include "engine/gl/Program.h"
#include "engine/render/FrameInfo.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

namespace refraction {

/** One glass id's optics as layers.glsl's GlassMaterial reads them (std430). */
struct GlassMaterialGpu {
    glm::vec4 ior;       ///< per channel; w: transmission
    glm::vec4 sigma;     ///< absorption per world unit; w: roughness
    glm::vec4 baseColor; ///< w: metallic
    glm::vec4 emissive;  ///< w: the solid (the character's index among the glass ones)
    glm::vec4 specular;  ///< KHR_materials_specular: colour, w: weight
    glm::vec4 layers;    ///< clearcoat, its roughness, iridescence, the film's index
    glm::vec4 sheen;     ///< colour, w: roughness
    glm::vec4 film;      ///< x: the film's thickness (nm)
    /** The normal map traced hits read: x its index in GpuState::tracedNormalMaps (-1: none), y
     *  its scale, z its texture coordinate set; its texture transform's rows. */
    glm::vec4 normalMap{-1.0f, 1.0f, 0.0f, 0.0f};
    glm::vec4 normalUv[2]{{1.0f, 0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f, 0.0f}};
};

/** The glass's extent and the overflow count, as refraction/glass_rectangle.glsl reads them
 *  (std430). */
struct GlassRectangleGpu {
    std::int32_t pixelMin[2], pixelMax[2]; ///< inclusive; empty while min > max
    std::int32_t boxMin[3], boxMax[3];     ///< view space, floats as ordered ints
    std::uint32_t overflowPixels;          ///< pixels over K in the walk
    std::uint32_t backRange[2], frontMin;  ///< the pair's depth ranges (float bits)
    std::uint32_t traceRays, traceSteps[2], traceMaxSteps; ///< the trace's counts (LayerStats)
    std::uint32_t walkedPixels, hybridTraced, hybridBy[4];  ///< the hybrid's (LayerStats)
};

struct GpuState {
    BvhPrograms bvh;          // the glass BVH's build and refit, the d_N cast
    gl::Program rectangleGrow; // the glass rectangle
    // The pair capture: its two geometry passes, or its one, and its resolve (PAIR_GATHERED 0, 1).
    gl::Program surface, surfaces, resolve[2];
    // The layers (layers.glsl): the capture and its depth maps for K = layerProgramsCapacity
    // (compiled in); the outline pass.
    gl::Program layersCapture, layersResolve, layersOutline;
    int layerProgramsCapacity = 0;
    /** The walk's variants by (capture: 0 the pair, else K; method; dispersion search;
     *  punctual lights). */
    using WalkKey = std::tuple<int, int, int, bool>;
    std::map<WalkKey, gl::Program> walkPrograms;
    /** The hybrid's trace pass, by the same key and whether its target adds samples up. */
    std::map<std::pair<WalkKey, bool>, gl::Program> handedOverTrace;
    /** The hybrid's handed-over pixels (walk.glsl's HandedOver): count, work groups, then one
     *  word a pixel; reallocated when the viewport grows. */
    gl::Buffer handedOver;
    /** The per-pixel layer arrays of layers.glsl, reallocated when the size or K changes. */
    struct LayerStorage {
        gl::Buffer heads;  // count, nearest front key, farthest back key: 3 words per pixel
        gl::Buffer depths; // K floats per pixel
        gl::Buffer attrs;  // K uvec2 per pixel
        glm::ivec2 size{0};
        int capacity = 0;
    } layers;
    gl::Buffer glassMaterials; // GlassMaterial (layers.glsl) per glass id, grown as needed
    /** This frame's glass ids per frame item (-1: not glass) and optics per id (one per
     *  character and material), refilled each frame in place (assignGlassIds). */
    std::vector<int> glassIds;
    std::vector<GlassMaterialGpu> glassOptics;
    bool warnedGlassIds = false; // the 256-id limit was reported
    /** The glass normal maps the trace reads (trace.glsl's uTracedNormalMaps), this frame. */
    std::vector<const gl::Texture*> tracedNormalMaps;
    bool warnedNormalMaps = false; // more than kTracedNormalMaps was reported
    gl::Framebuffer framebuffer;
    /** The scene's colour, read to convert it into the walk's single-precision target. */
    gl::Framebuffer sceneColorRead;
    gl::VertexArray emptyVao;
    gl::Buffer rectangle{sizeof(GlassRectangleGpu)};
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
