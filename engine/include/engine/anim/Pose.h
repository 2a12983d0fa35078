// A sampled pose: per-node local transforms, world transforms and morph weights. No GL.
#pragma once

#include "engine/scene/Model.h"

#include <glm/glm.hpp>

#include <vector>

namespace anim {

/** Every node's state for one instant. Build with restPose(), then applyClip() and
 *  updateWorld(). Indices follow Model::nodes. */
struct Pose {
    std::vector<scene::Trs> local;
    /** 1 while the node's local transform is the file's exact matrix (no channel targets it). */
    std::vector<std::uint8_t> useRestMatrix;
    std::vector<glm::dmat4> world; ///< node space -> world space
    /** Morph weights per node (empty for nodes without a morphing mesh). */
    std::vector<std::vector<double>> weights;
    /** Parents before children: the order updateWorld() walks. */
    std::vector<int> order;
};

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

/** restPose + applyClip + updateWorld in one call (clip -1: rest pose). */
Pose evaluate(const scene::Model& model, int clip, double time);

} // namespace anim
