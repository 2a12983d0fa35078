// Flat normals, unwelding and tangent generation for primitives the file left incomplete.
#include "MeshGeneration.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace asset::detail {
namespace {

template <class T> void expand(std::vector<T>& values, const std::vector<std::uint32_t>& indices) {
    if (values.empty())
        return;
    std::vector<T> expanded;
    expanded.reserve(indices.size());
    for (std::uint32_t index : indices)
        expanded.push_back(values[index]);
    values = std::move(expanded);
}

glm::vec3 anyPerpendicular(glm::vec3 n) {
    const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(axis, n));
}

} // namespace

void unweld(scene::Primitive& p) {
    const std::vector<std::uint32_t>& idx = p.indices;
    expand(p.positions, idx);
    expand(p.normals, idx);
    expand(p.tangents, idx);
    expand(p.uv0, idx);
    expand(p.uv1, idx);
    for (int s = 0; s < 2; ++s) {
        expand(p.joints[std::size_t(s)], idx);
        expand(p.weights[std::size_t(s)], idx);
    }
    for (scene::MorphTarget& target : p.targets) {
        expand(target.positions, idx);
        expand(target.normals, idx);
        expand(target.tangents, idx);
    }
    for (std::size_t i = 0; i < p.indices.size(); ++i)
        p.indices[i] = std::uint32_t(i);
}

void computeFlatNormals(scene::Primitive& p) {
    p.normals.assign(p.positions.size(), glm::vec3(0, 0, 1));
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        const glm::vec3 a = p.positions[p.indices[t]];
        const glm::vec3 b = p.positions[p.indices[t + 1]];
        const glm::vec3 c = p.positions[p.indices[t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        const float length = glm::length(n);
        const glm::vec3 unit = length > 0.0f ? n / length : glm::vec3(0, 0, 1);
        for (int k = 0; k < 3; ++k)
            p.normals[p.indices[t + std::size_t(k)]] = unit;
    }
}

void generateTangents(scene::Primitive& p, int texCoord) {
    const std::vector<glm::vec2>& uv = texCoord == 1 ? p.uv1 : p.uv0;
    const std::size_t n = p.positions.size();
    std::vector<glm::vec3> sdir(n, glm::vec3(0.0f)), tdir(n, glm::vec3(0.0f));
    if (uv.size() == n) {
        for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
            const std::uint32_t i0 = p.indices[t], i1 = p.indices[t + 1], i2 = p.indices[t + 2];
            const glm::vec3 e1 = p.positions[i1] - p.positions[i0];
            const glm::vec3 e2 = p.positions[i2] - p.positions[i0];
            const glm::vec2 d1 = uv[i1] - uv[i0];
            const glm::vec2 d2 = uv[i2] - uv[i0];
            const float det = d1.x * d2.y - d2.x * d1.y;
            if (std::abs(det) < 1e-20f)
                continue;
            const float r = 1.0f / det;
            const glm::vec3 s = (e1 * d2.y - e2 * d1.y) * r;
            const glm::vec3 u = (e2 * d1.x - e1 * d2.x) * r;
            for (std::uint32_t i : {i0, i1, i2}) {
                sdir[i] += s;
                tdir[i] += u;
            }
        }
    }
    p.tangents.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 normal = p.normals[i];
        glm::vec3 t = sdir[i] - normal * glm::dot(normal, sdir[i]);
        const float length = glm::length(t);
        t = length > 1e-12f ? t / length : anyPerpendicular(normal);
        const float w = glm::dot(glm::cross(normal, t), tdir[i]) < 0.0f ? -1.0f : 1.0f;
        p.tangents[i] = glm::vec4(t, w);
    }
    p.generatedTangents = true;
}

} // namespace asset::detail
