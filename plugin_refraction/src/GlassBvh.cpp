// The frame's glass BVH: the world mesh, its GPU build (Morton codes, bitonic sort, Karras'
// hierarchy), the bottom-up refit and the cost that decides a rebuild, the d_N cast.
#include "GlassBvh.h"

#include "Shared.h"

#include "engine/gl/Commands.h"
#include "engine/gl/ProgramCache.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <string>

namespace refraction {

namespace {

constexpr std::size_t kVertexFloats = 12; // common/vertex.glsl: position, normal, tangent
constexpr std::uint32_t kCostOffset = 6 * sizeof(std::uint32_t); // glass_bvh.comp.glsl's cost
constexpr std::uint32_t kCostNodes = 8; // nodes a thread of the cost stage sums

std::uint32_t groups(std::uint32_t threads) {
    return (threads + 63) / 64;
}

/** One stage over `threads` (its buffers bound), then a barrier for the next. */
void run(const gl::Program& stage, std::uint32_t threads, std::uint32_t triangles) {
    stage.use();
    stage.set("uCount", int(threads));
    stage.set("uTriangles", int(triangles));
    gl::dispatch(groups(threads));
    gl::memoryBarrier(gl::BarrierStorage);
}

} // namespace

GlassBvh::GlassBvh(std::span<const scene::Primitive* const> parts) {
    std::vector<glm::vec4> uvs;
    for (const scene::Primitive* p : parts) {
        const auto base = mVertexCount;
        mBases.push_back(base);
        mVertexCount += std::uint32_t(p->positions.size());
        for (std::size_t v = 0; v < p->positions.size(); ++v)
            uvs.push_back(p->uvs(v));
        for (std::uint32_t index : p->indices)
            mTriangleIndices.push_back(base + index);
        mPartTriangles.push_back(std::uint32_t(p->indices.size() / 3));
    }
    const std::size_t n = std::max<std::size_t>(triangleCount(), 1), nodes = 2 * n - 1;
    mPairs = std::bit_ceil(std::uint32_t(n));
    mVertices = gl::Buffer(std::max<std::size_t>(mVertexCount, 1) * kVertexFloats * sizeof(float));
    mIndices = gl::Buffer(std::max<std::size_t>(mTriangleIndices.size(), 3) * sizeof(std::uint32_t),
                          mTriangleIndices.data());
    mNodes = gl::Buffer(nodes * sizeof(Bvh::Node));
    mOrder = gl::Buffer(mPairs * sizeof(std::uint32_t));
    mKeys = gl::Buffer(mPairs * sizeof(std::uint32_t));
    mParents = gl::Buffer(nodes * sizeof(std::int32_t));
    mVisits = gl::Buffer(n * sizeof(std::uint32_t));
    mBounds = gl::Buffer(nodes * 2 * sizeof(glm::vec4));
    mPackedBounds = gl::Buffer((nodes + 4) * sizeof(glm::uvec4)); // and two frames
    mPackedBounds.fill(nodes * sizeof(glm::uvec4), 16, 0u);
    mLeafCorners = gl::Buffer(n * 3 * sizeof(glm::vec4));
    mBuild = gl::Buffer(8 * sizeof(std::uint32_t));
    mTriangleTags = gl::Buffer(n * sizeof(std::uint32_t));
    mDistances = gl::Buffer(std::max<std::size_t>(mVertexCount, 1) * sizeof(float));
    uvs.resize(std::max<std::size_t>(uvs.size(), 1));
    mUvs = gl::Buffer(uvs.size() * sizeof(glm::vec4), uvs.data());
}

void GlassBvh::gather(std::size_t i, const gl::Buffer& vertices, std::uint32_t count,
                      const glm::mat4& world, const BvhPrograms& programs) const {
    const gl::Program& gather = *programs.gather;
    gather.use();
    gather.set("uWorld", world);
    gather.set("uNormalMatrix", glm::mat3(glm::transpose(glm::inverse(world))));
    gather.set("uBase", int(mBases[i]));
    gather.set("uVertexCount", int(count));
    gl::bindStorage(gl::slot::kVertices, vertices);
    gl::bindStorage(slot::kWorldMesh, mVertices);
    gl::dispatch(groups(count));
}

core::Result<BvhPrograms> BvhPrograms::from(gl::ProgramCache& programs) {
    BvhPrograms kept;
    for (std::size_t stage = 0; stage < kept.stages.size(); ++stage) {
        auto program = programs.compute("refraction/glass_bvh.comp.glsl",
                                        {"BVH_STAGE " + std::to_string(stage + 1)});
        if (!program)
            return program.error();
        kept.stages[stage] = *program;
    }
    auto gather = programs.compute("refraction/mesh_gather.comp.glsl");
    auto cast = programs.compute("refraction/normal_distance.comp.glsl");
    if (!gather || !cast)
        return !gather ? gather.error() : cast.error();
    kept.gather = *gather;
    kept.cast = *cast;
    return kept;
}

void GlassBvh::build(const BvhPrograms& programs) {
    const std::uint32_t n = triangleCount();
    mBuild.fill(0, 3, std::uint32_t(INT32_MAX)); // empty centroid box: min > max
    mBuild.fill(12, 3, std::uint32_t(INT32_MIN));
    run(*programs.stages[0], n, n);
    run(*programs.stages[1], mPairs, n);
    const gl::Program& sort = *programs.stages[2];
    sort.use();
    for (std::uint32_t size = 2; size <= mPairs; size *= 2)
        for (std::uint32_t stride = size / 2; stride > 0; stride /= 2) {
            sort.set("uSortSize", int(size));
            sort.set("uSortStride", int(stride));
            run(sort, mPairs, n);
        }
    run(*programs.stages[3], n, n);
    mRebuild = false;
    ++mBuilds;
}

void GlassBvh::refit(const BvhPrograms& programs) {
    // The frame the last refit left (bvh.glsl's packedBoxes), then the refit.
    const std::size_t frame = (2 * std::size_t(triangleCount()) - 1) * sizeof(glm::uvec4);
    gl::memoryBarrier(gl::BarrierBufferUpdate);
    mPackedBounds.copy(frame + 2 * sizeof(glm::uvec4), frame, 2 * sizeof(glm::uvec4));
    mVisits.fill(0, triangleCount(), 0u);
    run(*programs.stages[4], triangleCount(), triangleCount());
}

void GlassBvh::readCosts() {
    // Fences pass in order: a tree's fresh measure is read no later than its later ones. Measures
    // of a tree since rebuilt are dropped.
    for (const bool fresh : {true, false})
        for (Measure& m : mMeasures) {
            if (!m.pending || m.fresh != fresh || !m.fence.passed())
                continue;
            m.pending = false;
            if (m.tree != mBuilds)
                continue;
            std::uint32_t cost = 0;
            std::memcpy(&cost, m.cost.download(kCostOffset, sizeof cost).data(), sizeof cost);
            if (fresh) {
                mFreshCost = std::max(double(cost), 1.0);
                mCostRatio = 1.0;
            } else if (mFreshCost > 0.0) {
                mCostRatio = double(cost) / mFreshCost;
                mRebuild = mRebuild || mCostRatio > kRebuildRatio;
            }
        }
}

void GlassBvh::update(const BvhPrograms& programs) {
    const std::uint32_t n = triangleCount();
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierBufferUpdate); // the gathered cages
    if (n == 0)
        return;
    readCosts();
    const bool fresh = mBuilds == 0 || mRebuild;
    bindForTraversal();
    gl::bindStorage(slot::kBvhBuild, mBuild); // glass_bvh.comp.glsl's own
    gl::bindStorage(slot::kBvhKeys, mKeys);
    gl::bindStorage(slot::kBvhParents, mParents);
    gl::bindStorage(slot::kBvhVisits, mVisits);
    if (fresh) {
        build(programs);
        mFreshCost = 0.0;
        refit(programs); // for the root's box: the frame of the packed boxes
    }
    refit(programs);
    // The cost, into the next measure not waiting on a read, every kMeasureEvery updates.
    Measure& m = mMeasures[mNext];
    if (!m.pending && (fresh || ++mUpdates % kMeasureEvery == 0)) {
        mNext = (mNext + 1) % mMeasures.size();
        m.cost.fill(kCostOffset, 1, 0u);
        gl::bindStorage(slot::kBvhBuild, m.cost); // the cost stage writes Build.cost
        run(*programs.stages[5], (2 * n - 1 + kCostNodes - 1) / kCostNodes, n);
        m.fence.insert();
        m.pending = true;
        m.fresh = fresh;
        m.tree = mBuilds;
    }
}

void GlassBvh::castNormalDistances(const BvhPrograms& programs) {
    const gl::Program& cast = *programs.cast;
    cast.use();
    bindForTraversal();
    gl::bindStorage(slot::kNormalDistances, mDistances);
    cast.set("uVertexCount", int(mVertexCount));
    gl::dispatch(groups(mVertexCount));
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierVertex);
}

void GlassBvh::bindForTraversal() const {
    gl::bindStorage(slot::kWorldMesh, mVertices);
    gl::bindStorage(slot::kWorldIndices, mIndices);
    gl::bindStorage(slot::kBvhNodes, mNodes);
    gl::bindStorage(slot::kBvhOrder, mOrder);
    gl::bindStorage(slot::kBvhBoxes, mBounds);
    gl::bindStorage(slot::kBvhLeafCorners, mLeafCorners);
    gl::bindStorage(slot::kBvhTags, mTriangleTags);
    gl::bindStorage(slot::kBvhPackedBoxes, mPackedBounds);
    gl::bindStorage(slot::kWorldUvs, mUvs);
}

void GlassBvh::setTags(std::span<const std::uint32_t> partTags) {
    if (std::equal(partTags.begin(), partTags.end(), mPartTags.begin(), mPartTags.end()))
        return;
    mPartTags.assign(partTags.begin(), partTags.end());
    std::vector<std::uint32_t> tags(std::max<std::size_t>(triangleCount(), 1), 0u);
    for (std::size_t part = 0, t = 0; part < mPartTags.size(); ++part)
        for (std::uint32_t k = 0; k < mPartTriangles[part]; ++k)
            tags[t++] = mPartTags[part];
    mTriangleTags.update(std::span<const std::uint32_t>(tags));
}

Bvh GlassBvh::download() const {
    gl::memoryBarrier(gl::BarrierBufferUpdate);
    const std::size_t n = std::max<std::size_t>(triangleCount(), 1), nodes = 2 * n - 1;
    Bvh tree;
    tree.nodes.resize(nodes);
    tree.order.resize(n);
    tree.parents.resize(nodes);
    std::memcpy(tree.nodes.data(), mNodes.download().data(), nodes * sizeof(Bvh::Node));
    std::memcpy(tree.order.data(), mOrder.download().data(), n * sizeof(std::uint32_t));
    std::memcpy(tree.parents.data(), mParents.download().data(), nodes * sizeof(std::int32_t));
    const std::vector<std::uint8_t> bounds = mBounds.download();
    for (std::size_t i = 0; i < nodes; ++i) {
        glm::vec4 box[2];
        std::memcpy(box, bounds.data() + i * sizeof box, sizeof box);
        tree.lo.emplace_back(box[0]);
        tree.hi.emplace_back(box[1]);
        std::int32_t children;
        std::memcpy(&children, &box[0].w, sizeof children);
        tree.children.push_back(children);
    }
    // The packed boxes in cells of their frame (bvh.glsl's bvhFrame, bvhPackedBox).
    const std::vector<std::uint8_t> packed = mPackedBounds.download();
    glm::vec4 frame[2];
    std::memcpy(frame, packed.data() + nodes * sizeof(glm::uvec4), sizeof frame);
    tree.frameLo = glm::vec3(frame[0]);
    const glm::vec3 extent = glm::vec3(frame[1]) - tree.frameLo;
    const float longest = std::max({extent.x, extent.y, extent.z});
    tree.cell = glm::max(extent, glm::vec3(1e-6f * longest + 1e-30f)) / 65535.0f;
    constexpr float kUnbounded = std::numeric_limits<float>::infinity();
    for (std::size_t i = 0; i < nodes; ++i) {
        glm::uvec4 q;
        std::memcpy(&q, packed.data() + i * sizeof q, sizeof q);
        const glm::uvec3 lo(q.x & 0xFFFFu, q.x >> 16, q.y & 0xFFFFu);
        const glm::uvec3 hi(q.y >> 16, q.z & 0xFFFFu, q.z >> 16);
        tree.packedLo.push_back(
            glm::mix(glm::vec3(lo), glm::vec3(-kUnbounded), glm::equal(lo, glm::uvec3(0u))));
        tree.packedHi.push_back(
            glm::mix(glm::vec3(hi), glm::vec3(kUnbounded), glm::equal(hi, glm::uvec3(0xFFFFu))));
    }
    if (n == 1)
        tree.parents[0] = -1;
    return tree;
}

} // namespace refraction
