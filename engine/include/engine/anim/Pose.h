// A sampled pose: per-node local transforms, world transforms and morph weights. No GL.
#pragma once

#include "engine/scene/Model.h"
#include "engine/scene/Performance.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>
#include <vector>

namespace anim {

/** One node's blend in progress: the weight each property (translation, rotation, scale, morph
 *  weights) has gathered from the blended layers, and the sums of the additive ones. */
struct NodeBlend {
    std::array<double, 4> weight{};
    std::array<double, 4> added{};
    glm::dvec3 addTranslation{0.0};
    glm::dquat addRotation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 addScale{0.0};
    std::vector<double> addWeights;
};

/** Every node's state for one instant. Build with restPose(), then evaluate() (or applyClip()
 *  and updateWorld()). Indices follow Model::nodes. */
struct Pose {
    std::vector<scene::Trs> local;
    /** 1 while the node's local transform is the file's exact matrix (no channel targets it). */
    std::vector<std::uint8_t> useRestMatrix;
    std::vector<glm::dmat4> world; ///< node space -> world space
    /** Morph weights per node (empty for nodes without a morphing mesh). */
    std::vector<std::vector<double>> weights;
    /** Parents before children: the order updateWorld() walks. */
    std::vector<int> order;
    /** The model-space travel accumulated root motion adds (the layers' weighted loops times
     *  their clip's travel); zero in the other modes. */
    glm::dvec3 travel{0.0};
    /** The model's materials, lights and cameras with the clips' KHR_animation_pointer
     *  channels played. Each list is a copy where a clip the performance plays animates one of
     *  its kind, else empty (the model's own apply). What every draw, pass, light and the
     *  reference read for this character (materialOf(), lightOf(), cameraOf()). */
    std::vector<scene::Material> materials;
    std::vector<scene::Light> lights;
    std::vector<scene::Camera> cameras;
    /** The blend's scratch, kept between evaluations so that they allocate nothing. */
    std::vector<NodeBlend> blend;
    /** One pointer property's blend: its blended value and weight, and the additive sum. */
    struct PointerBlend {
        int object = -1, slot = -1;
        scene::PointerProperty property = scene::PointerProperty::BaseColor;
        glm::dvec4 value{0.0}, added{0.0};
        double weight = 0.0, addedWeight = 0.0;
    };
    std::vector<PointerBlend> pointers; ///< the properties this evaluation played
    std::vector<double> mask, samples, firstFrame;
};

/** Material `material` of `model` as `pose` shows it: its animated copy, else the model's; null
 *  for -1 (the default material). */
const scene::Material* materialOf(const scene::Model& model, const Pose& pose, int material);
/** Light `light` (KHR_lights_punctual) and camera `camera` of `model` as `pose` shows them. */
const scene::Light& lightOf(const scene::Model& model, const Pose& pose, int light);
const scene::Camera& cameraOf(const scene::Model& model, const Pose& pose, int camera);

/** The model's rest pose: local transforms and morph weights from the file (node weights
 *  override mesh defaults), world matrices computed. */
Pose restPose(const scene::Model& model);

/** Resets `pose` to rest and applies clip `clip` (an index into model.animations) at `time`
 *  seconds. Does not update world matrices. */
void applyClip(const scene::Model& model, int clip, double time, Pose& pose);

/** World matrices through the hierarchy: world(n) = world(parent) * local(n). */
void updateWorld(const scene::Model& model, Pose& pose);

/** Skin matrices of mesh node `meshNode` (which must have a skin):
 *  skinMatrix[j] = inverse(world(meshNode)) * world(joint j) * inverseBind[j]. They map bind
 *  space to the mesh node's space. */
std::vector<glm::dmat4> skinMatrices(const scene::Model& model, const Pose& pose, int meshNode);

/** The same into `out` (resized; no allocation once it is large enough), in single precision
 *  for upload. */
void skinMatrices(const scene::Model& model, const Pose& pose, int meshNode,
                  std::vector<glm::mat4>& out);

/** The pose of `model` playing `performance` at scene time `sceneTime`, world matrices updated:
 *  the one evaluator every renderer, tool and reference poses characters with. Layers blend as
 *  three.js's AnimationMixer blends actions: per property, a running weighted average (slerp for
 *  rotations, along the shorter arc); where the weights sum under one, the rest pose fills the
 *  remainder; additive layers then add their change from their clip's first frame. */
void evaluate(const scene::Model& model, const scene::Performance& performance, double sceneTime,
              Pose& pose);
Pose evaluate(const scene::Model& model, const scene::Performance& performance, double sceneTime);

/** The pose of one clip at clip time `time` (clip -1: rest pose), world matrices updated. */
Pose evaluate(const scene::Model& model, int clip, double time);

/** The node whose horizontal travel root motion moves for `clip`: the shallowest node a
 *  translation channel of the clip drives, among the skins' joints when the model has skins;
 *  -1 when none. */
int motionNode(const scene::Model& model, int clip);

} // namespace anim
