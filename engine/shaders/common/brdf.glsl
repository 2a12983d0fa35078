// Metallic-roughness shading with image-based lighting (split sum; analytic environment BRDF).
#ifndef COMMON_BRDF_GLSL
#define COMMON_BRDF_GLSL
#include "common/environment.glsl"

// Karis' analytic fit of the split-sum environment BRDF scale and bias.
vec2 environmentBrdf(float NoV, float roughness) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
    return vec2(-1.04, 1.04) * a004 + r.zw;
}

vec3 shadeMetallicRoughness(vec3 baseColor, float metallic, float roughness, float occlusion,
                            vec3 N, vec3 V) {
    float NoV = clamp(dot(N, V), 1e-4, 1.0);
    vec3 F0 = mix(vec3(0.04), baseColor, metallic);
    vec2 ab = environmentBrdf(NoV, roughness);
    vec3 specular = environmentRadiance(reflect(-V, N), roughness) * (F0 * ab.x + ab.y);
    vec3 diffuse = environmentIrradiance(N) * baseColor * (1.0 - metallic);
    return (diffuse + specular) * occlusion;
}
#endif
