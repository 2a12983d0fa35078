// The one structure over the frame's deformed glass: every glass part's deformed surface as drawn
// (refined under subdivision) gathered into one world-space mesh, and a BVH over its static
// triangles built on the GPU (a linear BVH from Morton codes, glass_bvh.comp.glsl) and refitted to
// the deformed vertices every frame, rebuilt when refitting has worn its surface-area cost past
// kRebuildRatio of the fresh tree's (a moving character, an exploding pose); no CPU-GPU sync in a
// frame (the cost is read back frames later, once a fence says it is there). ISR's d_N is cast
// against it (one ray per vertex along -N, exact nearest hit). Private to the plugin.
#pragma once

#include "engine/core/Result.h"
#include "engine/gl/Buffer.h"
#include "engine/gl/Program.h"
#include "engine/gl/Query.h"
#include "engine/scene/Mesh.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace gl {
class ProgramCache;
}

namespace refraction {

/** A BVH over triangles as the GPU holds it, read back (tests, tools). Internal nodes
 *  0..n-2 (node 0 the root), leaf k (the k-th triangle in Morton order) node n-1+k. */
struct Bvh {
    struct Node {
        std::int32_t left = -1, right = -1; ///< children; -1 for a leaf
        std::int32_t first = 0, count = 0;  ///< leaf: range in `order`
    };
    std::vector<Node> nodes;
    std::vector<std::uint32_t> order; ///< triangle indices, leaves' ranges
    std::vector<glm::vec3> lo, hi;    ///< each node's box
    /** Each inner node's children as its box holds them for the traversal (bvh.glsl's
     *  BvhBox): gamma << 2 | left is a leaf << 1 | right is a leaf. */
    std::vector<std::int32_t> children;
    /** Each node's box as the traversal reads it (bvh.glsl's packedBoxes), in cells of the
     *  frame; infinite where it leaves the frame. */
    std::vector<glm::vec3> packedLo, packedHi;
    glm::vec3 frameLo{0.0f}, cell{0.0f}; ///< bvh.glsl's bvhFrame
    std::vector<std::int32_t> parents;   ///< -1 for the root
};

/** The compute programs the structure runs (glass_bvh.comp.glsl's stages, the d_N cast). */
struct BvhPrograms {
    std::array<const gl::Program*, 6> stages{}; ///< BVH_STAGE 1-6
    /** mesh_gather.comp.glsl, normal_distance.comp.glsl */
    const gl::Program *gather = nullptr, *cast = nullptr;
    /** The variants from the program cache `programs` (each compiled the first time asked). */
    static core::Result<BvhPrograms> from(gl::ProgramCache& programs);
};

class GlassBvh {
public:
    /** A tree whose cost has grown past this ratio of the fresh tree's is rebuilt. Measured
     *  (gl_glass_bvh, llvmpipe): CesiumMan walking reaches it about once in two seconds, and a
     *  build with its two refits costs what about 30 refits do (12.0-12.8 against 0.38-0.40
     *  ms), while every ray through a tree worn to 1.5 pays up to half as much again; two
     *  characters that crossed and parted reach 2.5, a scrambled pose 171. */
    static constexpr double kRebuildRatio = 1.5;
    /** The cost is measured every this many updates (and right after a build): at level 2 on
     *  CesiumMan a measure cost 1.2-2 ms, a fifth of the update, every frame. */
    static constexpr int kMeasureEvery = 4;

    /** The parts' static topology, one after another (vertex `base(i) + v` is part i's vertex
     *  v). */
    explicit GlassBvh(std::span<const scene::Primitive* const> parts);

    /** Where part i's vertices start in the world mesh and in distances(). */
    std::uint32_t base(std::size_t i) const { return mBases[i]; }
    /** Copies part i's deformed vertices (`count` in its mesh node's space, placed by `world`)
     *  into the world mesh at base(i). No sync. */
    void gather(std::size_t i, const gl::Buffer& vertices, std::uint32_t count,
                const glm::mat4& world, const BvhPrograms& programs) const;
    /** Builds the tree from the gathered mesh when it has none or its cost has worn past
     *  kRebuildRatio, else refits it; then, every kMeasureEvery updates and after a build,
     *  measures its cost (read back frames later). */
    void update(const BvhPrograms& programs);
    /** Each part's tag, uploaded per triangle when they change: its glass id
     *  (glass_materials.glsl), or kOpaqueTag (Shared.h) with an opaque part's material factors
     *  (bits 0-20 the square root of its base colour, 7 a channel, red lowest; 21-25
     *  roughness, 26-29 metallic) and kOpaqueTextured where it has a base colour texture. */
    void setTags(std::span<const std::uint32_t> partTags);
    /** Binds what a traversal reads (bvh.glsl, trace.glsl) at their slots (Shared.h). */
    void bindForTraversal() const;
    /** d_N (world units) per world-mesh vertex into distances(). */
    void castNormalDistances(const BvhPrograms& programs);

    const gl::Buffer& distances() const { return mDistances; }
    /** The world mesh (common/vertex.glsl's layout) and its triangles' indices into it. */
    const gl::Buffer& mesh() const { return mVertices; }
    std::span<const std::uint32_t> triangles() const { return mTriangleIndices; }
    std::uint32_t triangleCount() const { return std::uint32_t(mTriangleIndices.size() / 3); }
    /** The world mesh's texture coordinates (TEXCOORD_0 in xy, _1 in zw; static), for the
     *  normal maps at traced hits. */
    const gl::Buffer& uvs() const { return mUvs; }
    /** Builds so far (the first included). */
    int builds() const { return mBuilds; }
    /** The last cost read back over its tree's when fresh (what decided the last rebuild until
     *  the new tree's is read; 0 before any). */
    double costRatio() const { return mCostRatio; }
    /** The tree as the GPU holds it now (synchronises: tests and tools). */
    Bvh download() const;

private:
    void build(const BvhPrograms& programs);
    void refit(const BvhPrograms& programs);
    void readCosts();

    std::vector<std::uint32_t> mBases;
    std::vector<std::uint32_t> mTriangleIndices; ///< into the world mesh
    std::vector<std::uint32_t> mPartTriangles;   ///< each part's triangle count
    std::vector<std::uint32_t> mPartTags;
    std::uint32_t mVertexCount = 0, mPairs = 1; ///< pairs: triangles padded to a power of two
    gl::Buffer mVertices, mIndices, mNodes, mOrder, mKeys, mParents, mVisits, mBounds,
        mPackedBounds, mLeafCorners, mBuild, mTriangleTags, mDistances, mUvs;
    /** A cost measured after an update (kMeasureEvery), read back once its fence has passed. */
    struct Measure {
        gl::Buffer cost{sizeof(std::uint32_t) * 8};
        gl::Fence fence;
        bool pending = false, fresh = false; ///< fresh: measured right after a build
        int tree = 0;                        ///< the build it measured (builds() then)
    };
    std::array<Measure, 3> mMeasures;
    std::size_t mNext = 0;
    bool mRebuild = false;
    int mBuilds = 0, mUpdates = 0;
    double mFreshCost = 0.0, mCostRatio = 0.0;
};

} // namespace refraction
