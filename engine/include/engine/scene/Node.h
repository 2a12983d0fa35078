// Engine-owned scene-graph node: local transform, hierarchy links, attached mesh/skin/camera.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>
#include <vector>

namespace scene {

/** Translation, rotation (unit quaternion), scale: the node's local space relative to its
 *  parent. Double precision, as the CPU reference works in doubles. */
struct Trs {
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};

    /** The local matrix T * R * S. */
    glm::dmat4 matrix() const;
};

/** A node of the hierarchy. Indices refer into the Model's arrays; -1 means none. */
struct Node {
    std::string name;
    int parent = -1;
    std::vector<int> children;
    /** Rest local transform. When the file gave a matrix, it is decomposed into `rest` too and
     *  `restMatrix` keeps the exact matrix, used while no animation targets the node. */
    Trs rest;
    glm::dmat4 restMatrix{1.0};
    bool hasMatrix = false;
    int mesh = -1;
    int skin = -1;
    int camera = -1;
    int light = -1;             ///< KHR_lights_punctual: index into Model::lights
    std::vector<float> weights; ///< node-level default morph weights (overrides the mesh's)
    /** EXT_mesh_gpu_instancing: T * R * S of each instance, in the node's space (the mesh is
     *  drawn once per instance at world * instance; skinned, the skinned mesh is placed so);
     *  empty: the mesh is drawn once, as usual. */
    std::vector<glm::dmat4> instances;

    /** How many times the node's mesh is drawn: once per instance, or once. */
    std::size_t drawCount() const { return instances.empty() ? 1 : instances.size(); }
    /** Draw `k`'s transform in the node's space (identity without instances). */
    glm::dmat4 instance(std::size_t k) const {
        return instances.empty() ? glm::dmat4(1.0) : instances[k];
    }
};

} // namespace scene
