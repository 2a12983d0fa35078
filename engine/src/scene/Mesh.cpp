// Topology of a primitive (engine/scene/Mesh.h).
#include "engine/scene/Mesh.h"

#include <algorithm>
#include <map>
#include <unordered_map>
#include <vector>

namespace scene {
namespace {

/** What moves vertex `v` of `p`: its rest position, skin influences and morph deltas. Copies of
 *  a vertex along a seam (split for their normals or texture coordinates) have the same. */
std::vector<float> deformationOf(const Primitive& p, std::size_t v) {
    std::vector<float> key{p.positions[v].x, p.positions[v].y, p.positions[v].z};
    for (int s = 0; s < p.influenceSets(); ++s) {
        const glm::uvec4 j = p.joints[std::size_t(s)][v];
        const glm::vec4 w = p.weights[std::size_t(s)][v];
        for (int c = 0; c < 4; ++c)
            if (w[c] != 0.0f) { // a joint of no weight moves nothing
                key.push_back(float(j[c]));
                key.push_back(w[c]);
            }
    }
    for (const MorphTarget& target : p.targets)
        if (!target.positions.empty())
            for (int c = 0; c < 3; ++c)
                key.push_back(target.positions[v][c]);
    return key;
}

} // namespace

bool isClosed(const Primitive& p) {
    if (p.indices.empty() || p.indices.size() % 3 != 0)
        return false;
    // Each vertex named by the first that deforms as it does: a seam's copies are one.
    std::map<std::vector<float>, std::uint32_t> first;
    std::vector<std::uint32_t> welded(p.vertexCount());
    for (std::size_t v = 0; v < welded.size(); ++v)
        welded[v] = first.emplace(deformationOf(p, v), std::uint32_t(v)).first->second;
    // Every directed edge once, and its reverse once: each edge between two triangles that
    // cross it in opposite directions (a consistently wound, closed surface).
    std::unordered_map<std::uint64_t, int> directed;
    directed.reserve(p.indices.size());
    auto key = [](std::uint32_t a, std::uint32_t b) { return std::uint64_t(a) << 32 | b; };
    for (std::size_t t = 0; t < p.indices.size(); t += 3) {
        const std::uint32_t c[3] = {welded[p.indices[t]], welded[p.indices[t + 1]],
                                    welded[p.indices[t + 2]]};
        if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
            continue; // degenerate (a fan's pole, say): it covers nothing
        for (int e = 0; e < 3; ++e)
            if (++directed[key(c[e], c[(e + 1) % 3])] > 1)
                return false; // an edge crossed twice one way
    }
    return std::all_of(directed.begin(), directed.end(), [&](const auto& edge) {
        return directed.count(key(std::uint32_t(edge.first), std::uint32_t(edge.first >> 32))) > 0;
    });
}

} // namespace scene
