// Engine-owned punctual lights (KHR_lights_punctual): a file's lights on its nodes, a scene
// file's in world space.
#pragma once

#include <glm/glm.hpp>

#include <string>

namespace scene {

/** The shadows a light casts (the engine's own: glTF says nothing of shadows, so a file's lights
 *  cast with these defaults). `resolution` is a map's texels per side (a point light has six
 *  maps), `softness` the radius of the filter over the map in texels (0: hard edges). */
struct LightShadow {
    bool enabled = true;
    int resolution = 1024;
    float softness = 1.5f;
    bool operator==(const LightShadow&) const = default;
};

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
    LightShadow shadow;
};

/** A light placed in the world: at `position` (point and spot), shining along `direction`
 *  (directional and spot, unit length). */
struct PlacedLight {
    Light light;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
};

} // namespace scene
