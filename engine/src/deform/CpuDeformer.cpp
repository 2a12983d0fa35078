// Reference morph + skin in double precision.
#include "engine/deform/CpuDeformer.h"

#include "engine/anim/Pose.h"
#include "engine/core/Check.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <cmath>

namespace deform {
namespace {

glm::dvec3 safeNormalize(const glm::dvec3& v) {
    const double length = glm::length(v);
    return length > 0.0 ? v / length : glm::dvec3(0.0, 0.0, 1.0);
}

} // namespace

DeformedPrimitive deformPrimitive(const scene::Primitive& p, std::span<const double> weights,
                                  std::span<const glm::dmat4> skin) {
    const std::size_t count = p.vertexCount();
    DeformedPrimitive out;
    out.positions.resize(count);
    out.normals.resize(count);
    const bool hasTangents = !p.tangents.empty();
    if (hasTangents)
        out.tangents.resize(count);

    // Morph (glTF §3.7.2.2): base + sum of weighted deltas.
    for (std::size_t v = 0; v < count; ++v) {
        out.positions[v] = glm::dvec3(p.positions[v]);
        out.normals[v] = glm::dvec3(p.normals[v]);
        if (hasTangents)
            out.tangents[v] = glm::dvec4(p.tangents[v]);
    }
    const std::size_t targets = std::min(weights.size(), p.targets.size());
    for (std::size_t t = 0; t < targets; ++t) {
        const double w = weights[t];
        if (w == 0.0)
            continue;
        const scene::MorphTarget& target = p.targets[t];
        for (std::size_t v = 0; v < count; ++v) {
            if (!target.positions.empty())
                out.positions[v] += w * glm::dvec3(target.positions[v]);
            if (!target.normals.empty())
                out.normals[v] += w * glm::dvec3(target.normals[v]);
            if (hasTangents && !target.tangents.empty())
                out.tangents[v] += glm::dvec4(w * glm::dvec3(target.tangents[v]), 0.0);
        }
    }

    // Skin: blended matrix per vertex; normals by its inverse transpose.
    const bool skinned = !skin.empty() && p.isSkinned();
    for (std::size_t v = 0; v < count; ++v) {
        glm::dmat4 blend(1.0);
        if (skinned) {
            blend = glm::dmat4(0.0);
            for (std::size_t s = 0; s < std::size_t(p.influenceSets()); ++s)
                for (int k = 0; k < 4; ++k) {
                    const double w = double(p.weights[s][v][k]);
                    if (w != 0.0) {
                        const std::uint32_t joint = p.joints[s][v][k];
                        ENGINE_CHECK(joint < skin.size(), "joint index past the skin");
                        blend += w * skin[joint];
                    }
                }
        }
        const glm::dmat3 linear(blend);
        out.positions[v] = glm::dvec3(blend * glm::dvec4(out.positions[v], 1.0));
        out.normals[v] = safeNormalize(glm::inverseTranspose(linear) * out.normals[v]);
        if (hasTangents) {
            const glm::dvec3 t = safeNormalize(linear * glm::dvec3(out.tangents[v]));
            out.tangents[v] = glm::dvec4(t, out.tangents[v].w);
        }
    }

    if (p.flatNormals)
        for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3) {
            const glm::dvec3& a = out.positions[p.indices[i]];
            const glm::dvec3& b = out.positions[p.indices[i + 1]];
            const glm::dvec3& c = out.positions[p.indices[i + 2]];
            const glm::dvec3 n = safeNormalize(glm::cross(b - a, c - a));
            for (int k = 0; k < 3; ++k)
                out.normals[p.indices[i + std::size_t(k)]] = n;
        }
    return out;
}

std::vector<DeformedInstance> deformScene(const scene::Model& model, const anim::Pose& pose) {
    std::vector<DeformedInstance> result;
    for (int node : model.meshNodes()) {
        const scene::Node& n = model.nodes[std::size_t(node)];
        DeformedInstance instance;
        instance.node = node;
        instance.mesh = n.mesh;
        std::vector<glm::dmat4> skin;
        if (n.skin >= 0)
            skin = anim::skinMatrices(model, pose, node);
        const std::vector<double>& weights = pose.weights[std::size_t(node)];
        for (const scene::Primitive& primitive : model.meshes[std::size_t(n.mesh)].primitives)
            instance.primitives.push_back(deformPrimitive(primitive, weights, skin));
        // EXT_mesh_gpu_instancing: the same deformed mesh at each instance's placement.
        for (std::size_t k = 0; k < n.drawCount(); ++k) {
            instance.meshToWorld = pose.world[std::size_t(node)] * n.instance(k);
            if (k + 1 < n.drawCount())
                result.push_back(instance);
            else
                result.push_back(std::move(instance));
        }
    }
    return result;
}

std::vector<DeformedInstance> deformCharacter(const scene::Character& character, double sceneTime) {
    ENGINE_CHECK(character.model != nullptr, "deformCharacter() of a character without a model");
    const anim::Pose pose = anim::evaluate(*character.model, character.performance, sceneTime);
    std::vector<DeformedInstance> instances = deformScene(*character.model, pose);
    const glm::dmat4 placement = character.transform();
    for (DeformedInstance& instance : instances)
        instance.meshToWorld = placement * instance.meshToWorld;
    return instances;
}

DeformedPrimitive toWorld(const DeformedPrimitive& primitive, const glm::dmat4& meshToWorld) {
    DeformedPrimitive out = primitive;
    const glm::dmat3 normalMatrix = glm::inverseTranspose(glm::dmat3(meshToWorld));
    for (std::size_t v = 0; v < out.positions.size(); ++v) {
        out.positions[v] = glm::dvec3(meshToWorld * glm::dvec4(out.positions[v], 1.0));
        out.normals[v] = safeNormalize(normalMatrix * out.normals[v]);
    }
    for (glm::dvec4& t : out.tangents)
        t = glm::dvec4(safeNormalize(glm::dmat3(meshToWorld) * glm::dvec3(t)), t.w);
    return out;
}

} // namespace deform
