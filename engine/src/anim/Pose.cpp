// Pose evaluation: rest state, clip application, world and skin matrices.
#include "engine/anim/Pose.h"

#include "engine/anim/Sampler.h"
#include "engine/core/Check.h"

#include <array>

namespace anim {
namespace {

/** Local transforms and morph weights back to the file's values. */
void resetToRest(const scene::Model& model, Pose& pose) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const scene::Node& node = model.nodes[i];
        pose.local[i] = node.rest;
        pose.useRestMatrix[i] = node.hasMatrix ? 1 : 0;
        if (node.mesh >= 0) {
            const scene::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
            const auto& source = node.weights.empty() ? mesh.defaultWeights : node.weights;
            pose.weights[i].assign(source.begin(), source.end());
        }
    }
}

} // namespace

Pose restPose(const scene::Model& model) {
    Pose pose;
    const std::size_t count = model.nodes.size();
    pose.local.resize(count);
    pose.useRestMatrix.resize(count);
    pose.world.assign(count, glm::dmat4(1.0));
    pose.weights.resize(count);
    resetToRest(model, pose);
    // Parents before children, over every root (not only the default scene's).
    std::vector<int> stack;
    for (int i = int(count) - 1; i >= 0; --i)
        if (model.nodes[std::size_t(i)].parent < 0)
            stack.push_back(i);
    while (!stack.empty()) {
        const int node = stack.back();
        stack.pop_back();
        pose.order.push_back(node);
        const auto& children = model.nodes[std::size_t(node)].children;
        stack.insert(stack.end(), children.rbegin(), children.rend());
    }
    updateWorld(model, pose);
    return pose;
}

void applyClip(const scene::Model& model, int clip, double time, Pose& pose) {
    ENGINE_CHECK(pose.local.size() == model.nodes.size(), "pose was built for another model");
    resetToRest(model, pose);
    if (clip < 0)
        return;
    ENGINE_CHECK(clip < int(model.animations.size()), "clip index out of range");
    const scene::Animation& animation = model.animations[std::size_t(clip)];
    std::array<double, 4> value{};
    for (const scene::AnimationChannel& channel : animation.channels) {
        if (channel.path == scene::AnimationPath::Pointer)
            continue; // the performance's evaluate() plays materials, lights and cameras
        const scene::AnimationSampler& sampler = animation.samplers[std::size_t(channel.sampler)];
        const std::size_t node = std::size_t(channel.node);
        scene::Trs& local = pose.local[node];
        pose.useRestMatrix[node] = 0;
        switch (channel.path) {
        case scene::AnimationPath::Translation:
            sample(sampler, time, false, std::span(value.data(), 3));
            local.translation = glm::dvec3(value[0], value[1], value[2]);
            break;
        case scene::AnimationPath::Scale:
            sample(sampler, time, false, std::span(value.data(), 3));
            local.scale = glm::dvec3(value[0], value[1], value[2]);
            break;
        case scene::AnimationPath::Rotation:
            sample(sampler, time, true, std::span(value.data(), 4));
            local.rotation = glm::dquat(value[3], value[0], value[1], value[2]);
            break;
        case scene::AnimationPath::Weights:
            pose.weights[node].resize(std::size_t(sampler.components));
            sample(sampler, time, false, pose.weights[node]);
            break;
        case scene::AnimationPath::Pointer:
            break;
        }
    }
}

void updateWorld(const scene::Model& model, Pose& pose) {
    for (int index : pose.order) {
        const std::size_t i = std::size_t(index);
        const scene::Node& node = model.nodes[i];
        const glm::dmat4 local = pose.useRestMatrix[i] ? node.restMatrix : pose.local[i].matrix();
        pose.world[i] = node.parent < 0 ? local : pose.world[std::size_t(node.parent)] * local;
    }
}

namespace {

/** skinMatrix[j] = inverse(world(meshNode)) * world(joint j) * inverseBind[j], as M. */
template <class M>
void fillSkinMatrices(const scene::Model& model, const Pose& pose, int meshNode,
                      std::vector<M>& out) {
    const scene::Node& node = model.nodes[std::size_t(meshNode)];
    ENGINE_CHECK(node.skin >= 0, "skinMatrices() needs a skinned mesh node");
    const scene::Skin& skin = model.skins[std::size_t(node.skin)];
    const glm::dmat4 worldToMesh = glm::inverse(pose.world[std::size_t(meshNode)]);
    out.resize(skin.joints.size());
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
        out[j] = M(worldToMesh * pose.world[std::size_t(skin.joints[j])] * skin.inverseBind[j]);
}

} // namespace

std::vector<glm::dmat4> skinMatrices(const scene::Model& model, const Pose& pose, int meshNode) {
    std::vector<glm::dmat4> result;
    fillSkinMatrices(model, pose, meshNode, result);
    return result;
}

void skinMatrices(const scene::Model& model, const Pose& pose, int meshNode,
                  std::vector<glm::mat4>& out) {
    fillSkinMatrices(model, pose, meshNode, out);
}

Pose evaluate(const scene::Model& model, int clip, double time) {
    Pose pose = restPose(model);
    applyClip(model, clip, time, pose);
    updateWorld(model, pose);
    return pose;
}

} // namespace anim
