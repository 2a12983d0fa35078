// BVH construction (CPU, once) and the per-frame refit and d_N ray casts (GPU).
#include "NormalDistance.h"

#include "engine/gl/Commands.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

namespace refraction {

namespace {

constexpr std::size_t kVertexFloats = 12; // common/vertex.glsl: position, normal, tangent

struct Box {
    glm::vec3 lo{3e38f}, hi{-3e38f};
    void grow(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
};

/** Reorders `part` (triangles) at the median of their centroids along the axis where those
 *  spread most; returns the size of the first half. */
int splitAtMedian(std::span<std::uint32_t> part, std::span<const glm::vec3> centroid) {
    glm::vec3 lo(3e38f), hi(-3e38f);
    for (std::uint32_t t : part) {
        lo = glm::min(lo, centroid[t]);
        hi = glm::max(hi, centroid[t]);
    }
    const glm::vec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const auto middle = part.begin() + std::ptrdiff_t(part.size() / 2);
    std::nth_element(part.begin(), middle, part.end(), [&](std::uint32_t a, std::uint32_t b) {
        return centroid[a][axis] < centroid[b][axis];
    });
    return int(part.size() / 2);
}

/** Reorders `part` (triangles, with their bounds) into two by the binned surface-area
 *  heuristic: of 16 planes per axis across the centroids, the one that minimises area times
 *  triangles summed over both sides; the median split where no plane separates them. Returns
 *  the size of the first part. */
int splitBySurfaceArea(std::span<std::uint32_t> part, std::span<const glm::vec3> centroid,
                       std::span<const Box> bounds) {
    Box spread;
    for (std::uint32_t t : part)
        spread.grow(centroid[t]);
    constexpr int kBins = 16;
    const auto binOf = [&](std::uint32_t t, int axis) {
        const float extent = spread.hi[axis] - spread.lo[axis];
        return std::min(kBins - 1, int(float(kBins) * (centroid[t][axis] - spread.lo[axis]) /
                                       std::max(extent, 1e-30f)));
    };
    const auto area = [](const Box& b) {
        const glm::vec3 d = glm::max(b.hi - b.lo, glm::vec3(0.0f));
        return d.x * d.y + d.y * d.z + d.z * d.x;
    };
    int bestAxis = -1, bestPlane = 0;
    float bestCost = 3e38f;
    for (int axis = 0; axis < 3; ++axis) {
        if (!(spread.hi[axis] > spread.lo[axis]))
            continue;
        Box bins[kBins];
        int counts[kBins] = {};
        for (std::uint32_t t : part) {
            bins[binOf(t, axis)].grow(bounds[t]);
            ++counts[binOf(t, axis)];
        }
        // Plane p puts bins [0, p) on the left, [p, kBins) on the right.
        float rightArea[kBins] = {};
        int rightCount[kBins] = {};
        Box right;
        for (int p = kBins - 1, count = 0; p > 0; --p) {
            right.grow(bins[p]);
            count += counts[p];
            rightArea[p] = area(right);
            rightCount[p] = count;
        }
        Box left;
        for (int p = 1, count = 0; p < kBins; ++p) {
            left.grow(bins[p - 1]);
            count += counts[p - 1];
            if (count == 0 || rightCount[p] == 0)
                continue;
            const float cost = area(left) * float(count) + rightArea[p] * float(rightCount[p]);
            if (cost < bestCost) {
                bestCost = cost;
                bestAxis = axis;
                bestPlane = p;
            }
        }
    }
    if (bestAxis < 0)
        return splitAtMedian(part, centroid);
    const auto middle = std::partition(
        part.begin(), part.end(), [&](std::uint32_t t) { return binOf(t, bestAxis) < bestPlane; });
    return int(middle - part.begin());
}

} // namespace

Bvh buildBvh(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices) {
    Bvh bvh;
    const std::size_t triangles = indices.size() / 3;
    bvh.order.resize(triangles);
    std::iota(bvh.order.begin(), bvh.order.end(), 0u);
    std::vector<glm::vec3> centroid(triangles);
    std::vector<Box> bounds(triangles);
    for (std::size_t t = 0; t < triangles; ++t) {
        for (std::size_t k = 0; k < 3; ++k)
            bounds[t].grow(positions[indices[3 * t + k]]);
        centroid[t] = (positions[indices[3 * t]] + positions[indices[3 * t + 1]] +
                       positions[indices[3 * t + 2]]) /
                      3.0f;
    }
    struct Task {
        int node, first, count, depth;
    };
    std::vector<int> depthOf;
    bvh.nodes.push_back({});
    depthOf.push_back(0);
    std::vector<Task> stack{{0, 0, int(triangles), 0}};
    while (!stack.empty()) {
        const Task task = stack.back();
        stack.pop_back();
        if (task.count <= 4) {
            bvh.nodes[std::size_t(task.node)] = {-1, -1, task.first, task.count};
            continue;
        }
        const auto part =
            std::span(bvh.order).subspan(std::size_t(task.first), std::size_t(task.count));
        // Shallow enough for the cast's stack (64 entries): from depth 32 on, halves.
        const int leftCount = task.depth < 32 ? splitBySurfaceArea(part, centroid, bounds)
                                              : splitAtMedian(part, centroid);
        const int left = int(bvh.nodes.size()), right = left + 1;
        bvh.nodes.push_back({});
        bvh.nodes.push_back({});
        depthOf.push_back(task.depth + 1);
        depthOf.push_back(task.depth + 1);
        bvh.nodes[std::size_t(task.node)] = {left, right, 0, 0};
        stack.push_back({left, task.first, leftCount, task.depth + 1});
        stack.push_back({right, task.first + leftCount, task.count - leftCount, task.depth + 1});
    }
    const int maxDepth = *std::max_element(depthOf.begin(), depthOf.end());
    for (int depth = maxDepth; depth >= 0; --depth) {
        const int first = int(bvh.levelNodes.size());
        for (std::size_t n = 0; n < bvh.nodes.size(); ++n)
            if (depthOf[n] == depth)
                bvh.levelNodes.push_back(int(n));
        bvh.levels.emplace_back(first, int(bvh.levelNodes.size()) - first);
    }
    return bvh;
}

NormalDistance::NormalDistance(std::span<const scene::Primitive* const> primitives) {
    for (const scene::Primitive* p : primitives) {
        const auto base = mVertexCount;
        mBases.push_back(base);
        mVertexCount += std::uint32_t(p->positions.size());
        for (std::uint32_t index : p->indices)
            mTriangleIndices.push_back(base + index);
    }
    mVertices = gl::Buffer(std::max<std::size_t>(mVertexCount, 1) * kVertexFloats * sizeof(float));
    mIndices = gl::Buffer(std::span<const std::uint32_t>(mTriangleIndices));
    mDistances = gl::Buffer(std::max<std::size_t>(mVertexCount, 1) * sizeof(float));
}

void NormalDistance::buildTree() {
    // Shaped by the first gathered pose, in world space: the primitives' rest positions are each
    // in their own mesh node's space (a static model's meshes all around one origin), and a tree
    // shaped there would bound, once refitted, boxes spanning the whole model.
    const std::vector<std::uint8_t> bytes = mVertices.download();
    std::vector<glm::vec3> positions(mVertexCount);
    glm::vec3 lo(3e38f), hi(-3e38f);
    for (std::uint32_t v = 0; v < mVertexCount; ++v) {
        std::memcpy(&positions[v], bytes.data() + std::size_t(v) * kVertexFloats * sizeof(float),
                    sizeof(glm::vec3));
        const glm::vec3& q = positions[v];
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
            positions[v] = glm::vec3(0.0f); // a degenerate skin: shaped at the origin
        lo = glm::min(lo, positions[v]);
        hi = glm::max(hi, positions[v]);
    }
    mEpsilon = mVertexCount > 0 ? 1e-4f * glm::length(hi - lo) : 0.0f;
    mBvh = buildBvh(positions, mTriangleIndices);
    mNodes = gl::Buffer(std::span<const Bvh::Node>(mBvh.nodes));
    mOrder = gl::Buffer(std::span<const std::uint32_t>(mBvh.order));
    mLevels = gl::Buffer(std::span<const std::int32_t>(mBvh.levelNodes));
    mBounds = gl::Buffer(mBvh.nodes.size() * 2 * sizeof(glm::vec4));
    mLeafCorners = gl::Buffer(std::max<std::size_t>(mBvh.order.size(), 1) * 3 * sizeof(glm::vec4));
}

void NormalDistance::gather(std::size_t i, const gl::Buffer& cage, std::uint32_t count,
                            const glm::mat4& world, const gl::Program& gather) const {
    gather.use();
    gather.set("uWorld", world);
    gather.set("uNormalMatrix", glm::mat3(glm::transpose(glm::inverse(world))));
    gather.set("uBase", int(mBases[i]));
    gather.set("uVertexCount", int(count));
    gl::bindStorage(0, cage);
    gl::bindStorage(1, mVertices);
    gl::dispatch((count + 63) / 64);
}

void NormalDistance::update(const gl::Program& refit, const gl::Program& cast) {
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierBufferUpdate); // the gathered cages
    if (!mNodes)
        buildTree();

    gl::bindStorage(0, mVertices);
    gl::bindStorage(1, mIndices);
    gl::bindStorage(2, mNodes);
    gl::bindStorage(3, mOrder);
    gl::bindStorage(4, mBounds);
    gl::bindStorage(5, mLevels);
    gl::bindStorage(7, mLeafCorners);
    refit.use();
    for (const auto& [first, count] : mBvh.levels) {
        refit.set("uFirst", first);
        refit.set("uCount", count);
        gl::dispatch(std::uint32_t((count + 63) / 64));
        gl::memoryBarrier(gl::BarrierStorage);
    }
    cast.use();
    gl::bindStorage(6, mDistances);
    cast.set("uVertexCount", int(mVertexCount));
    cast.set("uEpsilon", mEpsilon);
    gl::dispatch((mVertexCount + 63) / 64);
    gl::memoryBarrier(gl::BarrierStorage | gl::BarrierVertex);
}

} // namespace refraction
