// Image-based lighting from the prefiltered equirectangular environment: mip level = roughness.
#ifndef COMMON_ENVIRONMENT_GLSL
#define COMMON_ENVIRONMENT_GLSL
#include "common/math.glsl"

// mip chain: level k holds GGX roughness k / (levels - 1)
layout(binding = ENVIRONMENT_UNIT) uniform sampler2D uEnvPrefiltered;
layout(binding = ENVIRONMENT_UNIT + 1) uniform sampler2D uEnvIrradiance; // cosine-convolved, small
uniform float uEnvLevels;
uniform float uEnvRotation;         // radians about +y
uniform float uEnvIntensity;

vec3 rotateEnv(vec3 d) {
    float c = cos(uEnvRotation), s = sin(uEnvRotation);
    return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

vec3 environmentRadiance(vec3 direction, float roughness) {
    float lod = clamp(roughness, 0.0, 1.0) * (uEnvLevels - 1.0);
    return uEnvIntensity * textureLod(uEnvPrefiltered, equirectUv(rotateEnv(direction)), lod).rgb;
}

vec3 environmentIrradiance(vec3 normal) {
    return uEnvIntensity * textureLod(uEnvIrradiance, equirectUv(rotateEnv(normal)), 0.0).rgb;
}
#endif
