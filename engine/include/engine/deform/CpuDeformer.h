// The CPU reference deformation (double precision): morph, then skin. It is the oracle the GPU
// deform pass is checked against; it is not used for rendering.
#pragma once

#include "engine/anim/Pose.h"
#include "engine/scene/Model.h"
#include "engine/scene/World.h"

#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace deform {

/** Deformed attributes of one primitive, same vertex order as the primitive. */
struct DeformedPrimitive {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;  ///< unit length
    std::vector<glm::dvec4> tangents; ///< unit xyz, w kept from the rest tangent; empty if none
};

/** Morphs (position += sum w_i dP_i, same for normal and tangent xyz) and then skins
 *  (blend of skin matrices by the vertex weights) one primitive. Positions are in the mesh
 *  node's space. Normals use the inverse transpose of the blended matrix, so they stay correct
 *  under non-uniform scale; flat-normal primitives recompute the face normal instead.
 *  `weights` may be shorter than the target count (missing weights are 0); `skin` is empty for
 *  an unskinned node. */
DeformedPrimitive deformPrimitive(const scene::Primitive& primitive,
                                  std::span<const double> weights,
                                  std::span<const glm::dmat4> skin);

/** One mesh node of the scene, deformed. */
struct DeformedInstance {
    int node = -1;
    int mesh = -1;
    glm::dmat4 meshToWorld{1.0}; ///< world(node): mesh space -> world space
    std::vector<DeformedPrimitive> primitives;
};

/** Deforms every mesh node of the default scene (Model::meshNodes() order) for `pose`. */
std::vector<DeformedInstance> deformScene(const scene::Model& model, const anim::Pose& pose);

/** A character of a world at scene time `sceneTime`: its model deformed in the pose of what it
 *  plays then (anim::evaluate), each instance's meshToWorld including the character's
 *  transform (so toWorld() gives the character's vertices in the world). */
std::vector<DeformedInstance> deformCharacter(const scene::Character& character,
                                              double sceneTime);

/** Positions and normals of `instance` taken to world space (normals renormalised). */
DeformedPrimitive toWorld(const DeformedPrimitive& primitive, const glm::dmat4& meshToWorld);

} // namespace deform
