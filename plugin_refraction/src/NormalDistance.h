// d_N for ISR, recomputed every frame because the mesh deforms: a BVH built once over the static
// topology of all of a character's glass primitives (shaped by their first pose, in world space),
// refitted on the GPU to their deformed vertices gathered in world space, then one ray per vertex
// along -N (exact nearest hit). Its cost grows with the character's triangles, not with its
// primitives. Private to the plugin.
#pragma once

#include "engine/gl/Buffer.h"
#include "engine/gl/Program.h"
#include "engine/scene/Mesh.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace refraction {

/** A BVH over triangles (median split of centroids), flattened for the GPU. */
struct Bvh {
    struct Node {
        std::int32_t left = -1, right = -1; ///< children; -1 for a leaf
        std::int32_t first = 0, count = 0;  ///< leaf: range in `order`
    };
    std::vector<Node> nodes;                 ///< node 0 is the root
    std::vector<std::uint32_t> order;        ///< triangle indices, leaves' ranges
    std::vector<std::int32_t> levelNodes;    ///< node indices grouped by depth, deepest first
    std::vector<std::pair<int, int>> levels; ///< (first, count) into levelNodes, deepest first
};

/** Builds the BVH of the triangles `indices` over `positions` (binned surface-area heuristic,
 *  leaves of at most 4 triangles). */
Bvh buildBvh(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices);

/** GPU state of one character's d_N: its glass primitives' cages, one after another (vertex
 *  `base(i) + v` is primitive i's vertex v), under one BVH. */
class NormalDistance {
public:
    explicit NormalDistance(std::span<const scene::Primitive* const> primitives);

    /** Where primitive i's vertices start in the combined cage and in distances(). */
    std::uint32_t base(std::size_t i) const { return mBases[i]; }

    /** Copies primitive i's deformed cage (`count` vertices in its mesh node's space, placed by
     *  `world`) into the combined cage at base(i) (`gather`: cage_gather.comp.glsl). No sync. */
    void gather(std::size_t i, const gl::Buffer& cage, std::uint32_t count, const glm::mat4& world,
                const gl::Program& gather) const;
    /** Refits the BVH to the gathered combined cage and writes d_N (world units) per vertex into
     *  distances(). `refit` and `cast` are bvh_refit.comp.glsl and normal_distance.comp.glsl.
     *  The first call builds the tree from the gathered cage (read back once). */
    void update(const gl::Program& refit, const gl::Program& cast);

    const gl::Buffer& distances() const { return mDistances; }
    /** The tree (empty before the first update()). */
    const Bvh& tree() const { return mBvh; }

private:
    void buildTree();

    Bvh mBvh;
    std::vector<std::uint32_t> mBases;
    std::vector<std::uint32_t> mTriangleIndices; ///< into the combined cage
    std::uint32_t mVertexCount = 0;
    float mEpsilon = 0.0f;
    gl::Buffer mVertices, mIndices, mNodes, mOrder, mLevels, mBounds, mLeafCorners, mDistances;
};

} // namespace refraction
