// Perspective camera: view and projection matrices, from a glTF camera node or framing bounds.
#pragma once

#include "engine/anim/Pose.h"
#include "engine/scene/Model.h"
#include "engine/scene/World.h"

#include <glm/glm.hpp>

#include <map>

#include <optional>

namespace render {

struct Camera {
    glm::mat4 view{1.0f};       ///< world -> view (camera at origin looking down -z)
    glm::mat4 projection{1.0f}; ///< view -> clip (OpenGL conventions)
    glm::vec3 position{0.0f};   ///< world
    float znear = 0.01f, zfar = 100.0f;
    float yfov = 0.8f; ///< radians
    glm::mat4 viewProjection() const { return projection * view; }
};

/** World-space axis-aligned box. */
struct Bounds {
    glm::vec3 min{1e30f}, max{-1e30f};
    bool empty() const { return min.x > max.x; }
    void add(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    glm::vec3 center() const { return 0.5f * (min + max); }
    float radius() const { return 0.5f * glm::length(max - min); }
};

/** Bounds of the default scene's deformed meshes over `clip` (sampled at `samples` times over
 *  its duration; the rest pose when clip < 0), via the CPU reference deformation. */
Bounds animatedBounds(const scene::Model& model, int clip, int samples = 16);

/** The box around the corners of `bounds` moved by `transform`. */
Bounds transformed(const Bounds& bounds, const glm::dmat4& transform);

/** Bounds of `model` over every clip `performance` plays: the union of their animatedBounds()
 *  (each kept in `perClip` under its index; the rest pose's under -1 when it plays none), in
 *  model space. Blends of the clips stay near their union; accumulated root motion moves it by
 *  the pose's travel. */
Bounds performanceBounds(const scene::Model& model, const scene::Performance& performance,
                         std::map<int, Bounds>& perClip, int samples = 16);

/** Bounds of every character of `world` over what it plays: performanceBounds() of each
 *  (clips computed once per model), its corners through the character's transform. */
Bounds worldBounds(const scene::World& world, int samples = 16);

/** The camera a scene file places, its near and far planes fitted to `bounds`. */
Camera worldCamera(const scene::WorldCamera& camera, float aspect, const Bounds& bounds);

/** `world`'s camera at scene time `time`: the character's file camera it looks through, as the
 *  character's performance poses it then, else its placement (worldCamera()). The world must
 *  have a camera. */
Camera sceneCamera(const scene::World& world, double time, float aspect, const Bounds& bounds);

/** Looks at the bounds' centre from the front (+z side, slightly above), far enough that the
 *  bounding sphere fits the vertical and horizontal field of view. */
Camera frameBounds(const Bounds& bounds, float aspect, float yfov = 0.7f, float azimuth = 0.0f,
                   float elevation = 0.15f, float distanceScale = 1.0f);

/** The first perspective camera node of the default scene posed by `pose` (nullopt when there
 *  is none). */
std::optional<Camera> gltfCamera(const scene::Model& model, const anim::Pose& pose, float aspect);

/** The perspective camera on node `node` posed by `pose`, its model placed in the world by
 *  `placement` (nullopt when the node has none, or an orthographic one); its yfov as the pose
 *  plays it. */
std::optional<Camera> nodeCamera(const scene::Model& model, const anim::Pose& pose, int node,
                                 const glm::dmat4& placement, float aspect);

} // namespace render
