// Camera construction.
#include "engine/render/Camera.h"

#include "engine/deform/CpuDeformer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace render {

Bounds animatedBounds(const scene::Model& model, int clip, int samples) {
    Bounds bounds;
    const double duration = clip >= 0 ? model.animations[std::size_t(clip)].duration : 0.0;
    const int count = clip >= 0 ? std::max(samples, 1) : 1;
    for (int i = 0; i < count; ++i) {
        const double time = count > 1 ? duration * double(i) / double(count - 1) : 0.0;
        for (const auto& instance : deform::deformScene(model, anim::evaluate(model, clip, time)))
            for (const auto& primitive : instance.primitives)
                for (const glm::dvec3& p : primitive.positions)
                    bounds.add(glm::vec3(instance.meshToWorld * glm::dvec4(p, 1.0)));
    }
    if (bounds.empty())
        bounds.add(glm::vec3(0.0f));
    return bounds;
}

Bounds transformed(const Bounds& bounds, const glm::dmat4& transform) {
    Bounds out;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? bounds.max.x : bounds.min.x,
                           (corner & 2) ? bounds.max.y : bounds.min.y,
                           (corner & 4) ? bounds.max.z : bounds.min.z);
        out.add(glm::vec3(transform * glm::dvec4(p, 1.0)));
    }
    return out;
}

Bounds performanceBounds(const scene::Model& model, const scene::Performance& performance,
                         std::map<int, Bounds>& perClip, int samples) {
    Bounds bounds;
    const auto add = [&](int clip) { // a clip played twice adds the same box again
        if (clip >= int(model.animations.size()))
            return;
        auto [it, added] = perClip.try_emplace(clip);
        if (added)
            it->second = animatedBounds(model, clip, samples);
        bounds.add(it->second.min);
        bounds.add(it->second.max);
    };
    for (const scene::Layer& layer : performance.layers)
        if (layer.clip >= 0)
            add(layer.clip);
    for (const scene::Transition& transition : performance.transitions)
        if (transition.to >= 0)
            add(transition.to);
    if (bounds.empty()) // no clip: the rest pose
        add(-1);
    return bounds;
}

Bounds worldBounds(const scene::World& world, int samples) {
    std::map<const scene::Model*, std::map<int, Bounds>> perModel;
    Bounds bounds;
    for (const scene::Character& character : world.characters) {
        const Bounds placed =
            transformed(performanceBounds(*character.model, character.performance,
                                          perModel[character.model.get()], samples),
                        character.transform());
        bounds.add(placed.min);
        bounds.add(placed.max);
    }
    if (bounds.empty())
        bounds.add(glm::vec3(0.0f));
    return bounds;
}

namespace {

/** The view depth at which the bottom edge of the view meets a ground `height` below the
 *  camera (no roll: the whole edge meets it at one depth); infinity where it does not. */
float groundDepth(const glm::mat4& view, float yfov, float height) {
    const glm::vec3 up = glm::mat3(view) * glm::vec3(0.0f, 1.0f, 0.0f);
    const float facing = up.y * std::tan(0.5f * yfov) + up.z;
    return height > 0.0f && facing > 0.0f ? height / facing
                                          : std::numeric_limits<float>::infinity();
}

} // namespace

Camera worldCamera(const scene::WorldCamera& camera, float aspect, const Bounds& bounds) {
    Camera c;
    c.yfov = camera.yfov;
    c.position = camera.position;
    glm::vec3 up(0, 1, 0);
    if (glm::length(glm::cross(glm::normalize(camera.target - camera.position), up)) < 1e-4f)
        up = glm::vec3(0, 0, -1); // looking straight up or down
    c.view = glm::lookAt(camera.position, camera.target, up);
    const float distance = glm::length(bounds.center() - camera.position);
    const float radius = std::max(bounds.radius(), 1e-3f);
    // In front of the bounds, and of the nearest ground the view shows (the ground plane
    // reaches beyond the bounds, under the camera's feet).
    const float ground = 0.9f * groundDepth(c.view, c.yfov, camera.position.y - bounds.min.y);
    c.znear =
        std::max(std::min(distance - 2.0f * radius, ground), std::max(distance, radius) * 0.005f);
    c.zfar = distance + 4.0f * radius;
    c.projection = glm::perspective(c.yfov, aspect, c.znear, c.zfar);
    return c;
}

Camera sceneCamera(const scene::World& world, double time, float aspect, const Bounds& bounds) {
    const scene::WorldCamera& placed = world.camera.value();
    if (placed.through && placed.through->character < world.characters.size()) {
        const scene::Character& c = world.characters[placed.through->character];
        if (auto camera = nodeCamera(*c.model, anim::evaluate(*c.model, c.performance, time),
                                     placed.through->node, c.transform(), aspect))
            return *camera;
    }
    return worldCamera(placed, aspect, bounds);
}

Camera frameBounds(const Bounds& bounds, float aspect, float yfov, float azimuth, float elevation,
                   float distanceScale) {
    Camera c;
    c.yfov = yfov;
    const float radius = std::max(bounds.radius(), 1e-3f);
    const float halfFov = 0.5f * std::min(yfov, 2.0f * std::atan(std::tan(0.5f * yfov) * aspect));
    const float distance = distanceScale * radius / std::sin(halfFov);
    const glm::vec3 direction(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                              std::cos(azimuth) * std::cos(elevation));
    c.position = bounds.center() + direction * distance;
    c.view = glm::lookAt(c.position, bounds.center(), glm::vec3(0, 1, 0));
    c.znear = std::max(distance - 4.0f * radius, distance * 0.01f);
    c.zfar = distance + 8.0f * radius;
    c.projection = glm::perspective(yfov, aspect, c.znear, c.zfar);
    return c;
}

std::optional<Camera> nodeCamera(const scene::Model& model, const anim::Pose& pose, int node,
                                 const glm::dmat4& placement, float aspect) {
    const scene::Node& n = model.nodes[std::size_t(node)];
    if (n.camera < 0)
        return std::nullopt;
    const scene::Camera& cam = anim::cameraOf(model, pose, n.camera);
    if (cam.type != scene::Camera::Type::Perspective)
        return std::nullopt;
    Camera c;
    glm::dmat4 world = placement * pose.world[std::size_t(node)];
    // Remove scale: a camera's frame is its node's rotation and translation.
    for (int i = 0; i < 3; ++i)
        world[i] = glm::dvec4(glm::normalize(glm::dvec3(world[i])), 0.0);
    c.view = glm::mat4(glm::inverse(world));
    c.position = glm::vec3(world[3]);
    c.yfov = float(cam.yfov);
    c.znear = float(cam.znear);
    c.zfar = cam.zfar > 0.0 ? float(cam.zfar) : float(cam.znear) * 1e4f;
    c.projection = glm::perspective(c.yfov, aspect, c.znear, c.zfar);
    return c;
}

std::optional<Camera> gltfCamera(const scene::Model& model, const anim::Pose& pose, float aspect) {
    const std::vector<int> nodes = model.cameraNodes();
    if (nodes.empty())
        return std::nullopt;
    return nodeCamera(model, pose, nodes.front(), glm::dmat4(1.0), aspect);
}

} // namespace render
