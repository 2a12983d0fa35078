// OpenSubdiv refinement of one primitive, built once from its rest topology: stencil tables that
// turn a deformed cage into the refined vertices, their limit positions and limit tangents, and
// the face-varying UVs and tangents, plus the refined triangles. The GPU deformer evaluates the
// tables every frame (OpenSubdiv's GL compute evaluator); tests evaluate them on the CPU.
#pragma once

#include "engine/core/Result.h"
#include "engine/scene/Mesh.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace deform {

/** Stencils in OpenSubdiv's layout: stencil s sums weights[offsets[s] + k] * source[indices[...]]
 *  for k < sizes[s]; duWeights and dvWeights (limit stencils only) give the two tangents. */
struct Stencils {
    std::vector<int> sizes, offsets, indices;
    std::vector<float> weights, duWeights, dvWeights;
    std::size_t count() const { return sizes.size(); }
};

/** One output vertex of the refined mesh: a refined vertex (position, normal) with one of its
 *  face-varying values (UV, tangent). Vertices on a UV seam appear once per side. */
struct RefinedCorner {
    std::uint32_t vertex = 0;
    std::uint32_t faceVarying = 0;
};

struct Subdivision {
    /** Cage vertices welded by position (glTF splits vertices at UV and normal seams; the
     *  refiner must see one vertex there or the surface tears): the primitive's vertex that
     *  stands for each welded vertex. Stencil indices below already name these vertices. */
    std::vector<std::uint32_t> representative;
    /** Triangles dropped because welding made them degenerate (two corners at one point). */
    std::size_t degenerateTriangles = 0;
    /** Level-`level` vertices from the cage's vertices (the primitive's own indices). */
    Stencils refine;
    /** Limit position, du and dv of each refined vertex from the refined vertices. */
    Stencils limit;
    /** Level-`level` face-varying values from the primitive's vertices (tangents follow the
     *  cage's deformed tangents through these). */
    Stencils faceVarying;
    /** True when du x dv points inside: the normal is dv x du instead. */
    bool flipNormals = false;
    std::vector<RefinedCorner> corners; ///< one per output vertex
    /** The refined mesh at rest: limit positions and normals, limit UVs, tangents, indices
     *  into `corners`, the source's material. No skin: the deformed cage carries it. */
    scene::Primitive rest;
};

/** Builds the Loop refinement (glTF primitives are triangle lists) of `primitive` to `level`
 *  (1..kMaxSubdivisionLevel). `what` names the primitive in errors, e.g. "mesh 'body'
 *  primitive 0". Fails on a topology OpenSubdiv rejects or a result over the limits. */
core::Result<Subdivision> buildSubdivision(const scene::Primitive& primitive, int level,
                                           const std::string& what);

/** The refined surface of a deformed cage, as the GPU deformer refines it (subdivision_pack):
 *  limit positions and normals (du x dv, flipped as `sub` says), the cage's tangents refined as
 *  face-varying values and made orthogonal to the normal; one vertex per `sub.corners`, in the
 *  order sub.rest's indices and texture coordinates name them. The cage in the primitive's
 *  vertex order (mesh space). */
struct RefinedSurface {
    std::vector<glm::dvec3> positions, normals;
    std::vector<glm::dvec4> tangents; ///< empty where the cage has none
};
RefinedSurface refineCage(const Subdivision& sub, std::span<const glm::dvec3> positions,
                          std::span<const glm::dvec4> tangents);

/** `stencils` evaluated by OpenSubdiv's CPU evaluator (Osd::CpuEvaluator) over `source`:
 *  `width` floats per element, `stride` floats apart, from float `offset`. Results are packed
 *  (`width` floats per stencil); du and dv are filled for limit stencils. */
struct Evaluated {
    std::vector<float> values, du, dv;
};
Evaluated evaluateOnCpu(const Stencils& stencils, const float* source, int offset, int width,
                        int stride);

} // namespace deform
