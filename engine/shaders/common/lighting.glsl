// The frame's punctual lights (KHR_lights_punctual, a scene file's "lights"), their shadow
// views and the table of the sheen layer's directional albedo: one storage buffer the renderer
// binds for every pass (render::LightingBuffer, which lays it out in C++), and the shadow
// atlases every pass that shades samples (render::bindShadowMaps).
#ifndef COMMON_LIGHTING_GLSL
#define COMMON_LIGHTING_GLSL

// LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT and SHEEN_TABLE_SIZE: render/Shared.h.
// Whether the program evaluates the punctual lights: compiled out for frames without any (a CPU
// rasteriser pays for an empty loop on every shaded pixel).
#ifndef PUNCTUAL_LIGHTS
#define PUNCTUAL_LIGHTS 1
#endif
// The types of light it has (each compiled in without the define): a frame of directional
// lights alone, say, leaves out the local lights' falloffs, cube faces and perspective maps.
#ifndef DIRECTIONAL_LIGHTS
#define DIRECTIONAL_LIGHTS 1
#endif
#ifndef POINT_LIGHTS
#define POINT_LIGHTS 1
#endif
#ifndef SPOT_LIGHTS
#define SPOT_LIGHTS 1
#endif
#define LOCAL_LIGHTS (POINT_LIGHTS || SPOT_LIGHTS)

struct PunctualLight {
    vec4 position;  // world; w: LIGHT_*
    vec4 direction; // where it shines (unit, world); w: range, 0 for unlimited
    vec4 radiance;  // colour * intensity; w: cosine of the outer cone angle
    vec4 cone;      // x: cosine of the inner cone angle, y: first shadow view (-1: none),
                    // z: the shadow filter's radius in texels
};
// One map of a light (render::ShadowView) and its tile in the atlases.
struct ShadowView {
    mat4 viewProjection;
    vec4 tile;  // the tile's corner (xy) and sides (zw) in atlas uv
    vec4 axis;  // perspective: the light's position; else distance = dot(axis.xyz, P) + axis.w
    vec4 texel; // x: a texel's world size at distance 1 (perspective) or anywhere; y: perspective;
                // z: the near plane's distance; w: the tile's side in texels
};
layout(std430, binding = LIGHTING_BINDING) readonly buffer Lighting {
    // E(NoV, roughness) of the sheen lobe, row r: roughness r / (size - 1), column c: NoV
    // c / (size - 1)
    float sheenAlbedoTable[SHEEN_TABLE_SIZE * SHEEN_TABLE_SIZE];
    uvec4 lightCount; // x
    ShadowView shadowViews[MAX_SHADOW_VIEWS];
    PunctualLight punctualLights[];
};

#include "common/shadows.glsl"

// The spot's cone falloff of its light toward -L (L: unit, toward the light).
float spotFalloff(PunctualLight light, vec3 L) {
    float t = clamp((dot(light.direction.xyz, -L) - light.radiance.w) /
                        max(light.cone.x - light.radiance.w, 1e-4),
                    0.0, 1.0);
    return t * t;
}

// Light `i` as it arrives at P (normal N): its radiance after the distance, range and cone
// falloffs and what its shadow maps say blocks or tints it, and the unit direction L toward it.
vec3 lightArriving(uint i, vec3 P, vec3 N, out vec3 L) {
#ifdef SKIP_LIGHTS // glass-bench --skip lights: no light arrives (nor its shadow)
    L = N;
    return vec3(0.0);
#endif
    PunctualLight light = punctualLights[i];
    float falloff = 1.0;
    L = -light.direction.xyz;
#if LOCAL_LIGHTS
    if (DIRECTIONAL_LIGHTS == 0 || int(light.position.w) != LIGHT_DIRECTIONAL) {
        vec3 toLight = light.position.xyz - P;
        float d2 = max(dot(toLight, toLight), 1e-8);
        L = toLight * inversesqrt(d2);
        falloff = 1.0 / d2;
        if (light.direction.w > 0.0) { // the extension's smooth window to zero at the range
            float x = d2 / (light.direction.w * light.direction.w);
            float window = clamp(1.0 - x * x, 0.0, 1.0);
            falloff *= window * window;
        }
#if SPOT_LIGHTS
        if (int(light.position.w) == LIGHT_SPOT)
            falloff *= spotFalloff(light, L);
#endif
        if (falloff <= 0.0)
            return vec3(0.0);
    }
#endif
    return light.radiance.rgb * falloff * lightShadow(light, P, N, L);
}

// The sheen lobe's albedo, bilinear in the table as render::sheenAlbedo reads it.
float sheenAlbedo(float NoV, float roughness) {
    vec2 x = clamp(vec2(NoV, roughness), 0.0, 1.0) * float(SHEEN_TABLE_SIZE - 1);
    ivec2 i = min(ivec2(x), ivec2(SHEEN_TABLE_SIZE - 2));
    vec2 f = x - vec2(i);
    int row = i.y * SHEEN_TABLE_SIZE + i.x;
    float lo = mix(sheenAlbedoTable[row], sheenAlbedoTable[row + 1], f.x);
    float hi = mix(sheenAlbedoTable[row + SHEEN_TABLE_SIZE],
                   sheenAlbedoTable[row + SHEEN_TABLE_SIZE + 1], f.x);
    return mix(lo, hi, f.y);
}
#endif
