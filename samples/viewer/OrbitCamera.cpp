// The viewer's orbit camera.
#include "OrbitCamera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace viewer {
namespace {

constexpr float kMaxElevation = 1.5533f; // 89 degrees

glm::vec3 direction(const Orbit& o) {
    return {std::sin(o.azimuth) * std::cos(o.elevation), std::sin(o.elevation),
            std::cos(o.azimuth) * std::cos(o.elevation)};
}

} // namespace

void OrbitCamera::frame(const render::Bounds& bounds, float aspect) {
    const render::Camera framed = render::frameBounds(bounds, aspect, mYfov);
    mRadius = std::max(bounds.radius(), 1e-3f);
    mHome = Orbit{bounds.center(), glm::length(framed.position - bounds.center()), 0.0f, 0.15f};
    mOrbit = mHome;
}

void OrbitCamera::orbit(glm::vec2 pixels, float viewportHeight) {
    const float radiansPerPixel = glm::pi<float>() / std::max(viewportHeight, 1.0f);
    mOrbit.azimuth -= pixels.x * radiansPerPixel;
    mOrbit.elevation =
        std::clamp(mOrbit.elevation + pixels.y * radiansPerPixel, -kMaxElevation, kMaxElevation);
}

void OrbitCamera::pan(glm::vec2 pixels, float viewportHeight) {
    const glm::vec3 forward = -direction(mOrbit);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    const float worldPerPixel =
        2.0f * mOrbit.distance * std::tan(0.5f * mYfov) / std::max(viewportHeight, 1.0f);
    mOrbit.target += (-pixels.x * right + pixels.y * up) * worldPerPixel;
}

void OrbitCamera::zoom(float steps) {
    mOrbit.distance =
        std::clamp(mOrbit.distance * std::pow(0.9f, steps), 0.05f * mRadius, 50.0f * mRadius);
}

void OrbitCamera::setOrbit(const Orbit& orbit) {
    mOrbit = orbit;
    mOrbit.elevation = std::clamp(orbit.elevation, -kMaxElevation, kMaxElevation);
    mOrbit.distance = std::max(orbit.distance, 1e-4f);
}

void OrbitCamera::look(const scene::WorldCamera& camera) {
    const glm::vec3 back = camera.position - camera.target;
    const float distance = glm::length(back);
    if (!(distance > 0.0f))
        return;
    Orbit o;
    o.target = camera.target;
    o.distance = distance;
    o.azimuth = std::atan2(back.x, back.z);
    o.elevation = std::asin(std::clamp(back.y / distance, -1.0f, 1.0f));
    setOrbit(o);
    mYfov = camera.yfov;
}

scene::WorldCamera OrbitCamera::placement() const {
    return {mOrbit.target + direction(mOrbit) * mOrbit.distance, mOrbit.target, mYfov};
}

render::Camera OrbitCamera::camera(float aspect) const {
    render::Camera c;
    c.yfov = mYfov;
    c.position = mOrbit.target + direction(mOrbit) * mOrbit.distance;
    c.view = glm::lookAt(c.position, mOrbit.target, glm::vec3(0, 1, 0));
    c.znear = std::max(mOrbit.distance - 4.0f * mRadius, mOrbit.distance * 0.01f);
    c.zfar = mOrbit.distance + 8.0f * mRadius;
    c.projection = glm::perspective(mYfov, aspect, c.znear, c.zfar);
    return c;
}

} // namespace viewer
