// BVH construction (CPU, once) and the per-frame refit and d_N ray casts (GPU).
#include "NormalDistance.h"

#include "engine/gl/Commands.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <numeric>

namespace refraction {

Bvh buildBvh(const scene::Primitive& p) {
    return buildBvh(p.positions, p.indices);
}

Bvh buildBvh(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices) {
    Bvh bvh;
    const std::size_t triangles = indices.size() / 3;
    bvh.order.resize(triangles);
    std::iota(bvh.order.begin(), bvh.order.end(), 0u);
    std::vector<glm::vec3> centroid(triangles);
    for (std::size_t t = 0; t < triangles; ++t)
        centroid[t] = (positions[indices[3 * t]] + positions[indices[3 * t + 1]] +
                       positions[indices[3 * t + 2]]) /
                      3.0f;
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
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (int i = task.first; i < task.first + task.count; ++i) {
            lo = glm::min(lo, centroid[bvh.order[std::size_t(i)]]);
            hi = glm::max(hi, centroid[bvh.order[std::size_t(i)]]);
        }
        const glm::vec3 extent = hi - lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        const auto begin = bvh.order.begin() + task.first;
        const auto middle = begin + task.count / 2;
        std::nth_element(begin, middle, begin + task.count, [&](std::uint32_t a, std::uint32_t b) {
            return centroid[a][axis] < centroid[b][axis];
        });
        const int left = int(bvh.nodes.size()), right = left + 1;
        bvh.nodes.push_back({});
        bvh.nodes.push_back({});
        depthOf.push_back(task.depth + 1);
        depthOf.push_back(task.depth + 1);
        bvh.nodes[std::size_t(task.node)] = {left, right, 0, 0};
        stack.push_back({left, task.first, task.count / 2, task.depth + 1});
        stack.push_back(
            {right, task.first + task.count / 2, task.count - task.count / 2, task.depth + 1});
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
    // The rest positions only shape the tree (each primitive in its own mesh space); the refit
    // bounds the deformed world-space vertices every frame.
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    for (const scene::Primitive* p : primitives) {
        const auto base = std::uint32_t(positions.size());
        mBases.push_back(base);
        positions.insert(positions.end(), p->positions.begin(), p->positions.end());
        for (std::uint32_t index : p->indices)
            indices.push_back(base + index);
    }
    mBvh = buildBvh(positions, indices);
    mVertexCount = std::uint32_t(positions.size());
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& v : positions) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    mEpsilon = 1e-4f * glm::length(hi - lo);
    mVertices = gl::Buffer(std::max<std::size_t>(mVertexCount, 1) * 12 * sizeof(float));
    mIndices = gl::Buffer(std::span<const std::uint32_t>(indices));
    mNodes = gl::Buffer(std::span<const Bvh::Node>(mBvh.nodes));
    mOrder = gl::Buffer(std::span<const std::uint32_t>(mBvh.order));
    mLevels = gl::Buffer(std::span<const std::int32_t>(mBvh.levelNodes));
    mBounds = gl::Buffer(mBvh.nodes.size() * 2 * sizeof(glm::vec4));
    mLeafCorners = gl::Buffer(std::max<std::size_t>(mBvh.order.size(), 1) * 3 * sizeof(glm::vec4));
    mDistances = gl::Buffer(std::max<std::size_t>(mVertexCount, 1) * sizeof(float));
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
    gl::memoryBarrier(gl::BarrierStorage); // the gathered cages

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
