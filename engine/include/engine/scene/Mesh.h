// Engine-owned mesh data: primitives with rest attributes, skin influences and morph deltas,
// all in the mesh's own (node-local) space. Filled by asset::loadGltf, read by deform and gl.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace scene {

/** One morph target's deltas, in mesh space. An attribute the target does not move is empty. */
struct MorphTarget {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec3> tangents; ///< xyz deltas; the base tangent's w is kept
};

/** A triangle list with per-vertex attributes. Every non-empty attribute array has
 *  vertexCount() entries. Strips and fans are converted to lists on import. */
struct Primitive {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  ///< always present (generated when the file has none)
    std::vector<glm::vec4> tangents; ///< xyz + handedness w; present when the file has them or a
                                     ///< normal map needs them (generated)
    std::vector<glm::vec2> uv0, uv1;
    /** Skin influences: set s holds joints s*4..s*4+3; joint indices index the node's skin's
     *  joint list. Weights are renormalised to sum to 1 over all sets. */
    std::array<std::vector<glm::uvec4>, 2> joints;
    std::array<std::vector<glm::vec4>, 2> weights;
    std::vector<std::uint32_t> indices; ///< three per triangle; generated for non-indexed input
    std::vector<MorphTarget> targets;
    int material = -1; ///< index into Model::materials, -1 for the default material
    /** KHR_materials_variants: the material of each of the model's variants (Model::variants),
     *  -2 where the variant keeps `material`; empty without mappings. */
    std::vector<int> variantMaterials;
    /** TEXCOORD_0 in xy and TEXCOORD_1 in zw of vertex `v` (zeros for a set it lacks). */
    glm::vec4 uvs(std::size_t v) const {
        const glm::vec2 a = v < uv0.size() ? uv0[v] : glm::vec2(0.0f);
        const glm::vec2 b = v < uv1.size() ? uv1[v] : glm::vec2(0.0f);
        return {a, b};
    }
    /** The material drawn under `variant` (-1: the file's default). */
    int materialFor(int variant) const {
        return variant >= 0 && std::size_t(variant) < variantMaterials.size() &&
                       variantMaterials[std::size_t(variant)] != -2
                   ? variantMaterials[std::size_t(variant)]
                   : material;
    }

    /** True when the file had no NORMAL: normals are flat (vertices unwelded per triangle) and
     *  deformation recomputes them from the deformed triangle. */
    bool flatNormals = false;
    /** True when TANGENT was generated (the file had none but a normal map needs them). */
    bool generatedTangents = false;
    /** POSITION accessor count in the file (differs from vertexCount() after unwelding). */
    std::size_t sourceVertexCount = 0;

    std::size_t vertexCount() const { return positions.size(); }
    std::size_t triangleCount() const { return indices.size() / 3; }
    /** Influence sets in use: 0 (not skinned), 1 (4 influences) or 2 (8 influences). */
    int influenceSets() const { return int(!joints[0].empty()) + int(!joints[1].empty()); }
    bool isSkinned() const { return influenceSets() > 0; }
    bool isMorphed() const { return !targets.empty(); }
};

/** Whether `p` bounds a solid in every pose: each edge lies between two triangles that cross
 *  it in opposite directions, where vertices that deform alike (the same rest position, skin
 *  influences and morph deltas: a seam's copies) count as one. From outside such a surface
 *  shows only its front faces, so a shadow map may leave its back faces out. Degenerate
 *  triangles (two corners that count as one) are left out: they cover nothing. */
bool isClosed(const Primitive& p);

/** A glTF mesh: primitives sharing one set of morph weights. */
struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
    std::vector<float> defaultWeights; ///< one per morph target (zeros when the file has none)
    std::vector<std::string> targetNames;

    std::size_t morphTargetCount() const { return defaultWeights.size(); }
};

} // namespace scene
