// The ground plane's surface (render::GroundPlane): a soft two-tone checker of `tileSize`
// squares, rough dielectric, lit by the environment and the lights; seen from V at `world`.
// The ground pass draws it; the refraction plugin shades it where a refracted ray meets it.
#ifndef COMMON_GROUND_GLSL
#define COMMON_GROUND_GLSL
#include "common/brdf.glsl"

vec3 groundColor(vec3 world, vec3 V, float tileSize) {
    vec2 cell = floor(world.xz / tileSize);
    vec3 base = mix(vec3(0.30), vec3(0.42), mod(cell.x + cell.y, 2.0));
    return shadeMetallicRoughness(base, 0.0, 0.8, 1.0, world, vec3(0.0, 1.0, 0.0), V);
}

#endif
