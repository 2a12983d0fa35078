// d_N for ISR, recomputed every frame because the mesh deforms: a BVH built once over the
// primitive's static topology, refitted on the GPU to the deformed vertices, then one ray per
// vertex along -N (exact nearest hit). Private to the plugin.
#pragma once

#include "engine/gl/Buffer.h"
#include "engine/gl/Program.h"
#include "engine/scene/Mesh.h"

#include <cstdint>
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

/** Builds the BVH of `primitive` from its rest positions (leaves of at most 4 triangles). */
Bvh buildBvh(const scene::Primitive& primitive);

/** GPU state of one primitive's d_N. */
class NormalDistance {
public:
    explicit NormalDistance(const scene::Primitive& primitive);

    /** Refits the BVH to `deformed` (the engine's deformed vertex buffer of this primitive) and
     *  writes d_N per vertex into distances(). `refit` and `cast` are bvh_refit.comp.glsl and
     *  normal_distance.comp.glsl. */
    void update(const gl::Buffer& deformed, const gl::Buffer& indices, const gl::Program& refit,
                const gl::Program& cast);

    const gl::Buffer& distances() const { return mDistances; }

private:
    Bvh mBvh;
    std::uint32_t mVertexCount;
    float mEpsilon;
    gl::Buffer mNodes, mOrder, mLevels, mBounds, mDistances;
};

} // namespace refraction
