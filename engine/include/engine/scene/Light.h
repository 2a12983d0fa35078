// Engine-owned punctual lights (KHR_lights_punctual): a file's lights on its nodes, a scene
// file's in world space.
#pragma once

#include <glm/glm.hpp>

#include <string>

namespace scene {

/** A light as the extension defines it: directional (intensity in lux), point or spot
 *  (candela), shining down -z of its node; `range` 0 is unlimited; a spot's cone falls off
 *  between innerConeAngle and outerConeAngle (radians from its axis). */
struct Light {
    enum class Type { Directional, Point, Spot } type = Type::Point;
    std::string name;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 0.0f;
    float innerConeAngle = 0.0f;
    float outerConeAngle = 0.7853982f;
};

/** A light placed in the world: at `position` (point and spot), shining along `direction`
 *  (directional and spot, unit length). */
struct PlacedLight {
    Light light;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
};

} // namespace scene
