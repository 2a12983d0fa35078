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

// The dielectric's specular lobe has reflectance `dielectricF0` at normal incidence and weight
// `specularWeight` (KHR_materials_specular: the F0 from the index of refraction times its colour,
// at most 1, and its factor; 0.04 and 1 in glTF's core model); a metal's F0 is its base colour.
vec3 shadeMetallicRoughnessSpecular(vec3 baseColor, float metallic, float roughness,
                                    float occlusion, vec3 N, vec3 V, vec3 dielectricF0,
                                    float specularWeight) {
    float NoV = clamp(dot(N, V), 1e-4, 1.0);
    vec2 ab = environmentBrdf(NoV, roughness);
    vec3 radiance = environmentRadiance(reflect(-V, N), roughness);
    vec3 dielectric = specularWeight * radiance * (min(dielectricF0, vec3(1.0)) * ab.x + ab.y);
    vec3 metal = radiance * (baseColor * ab.x + ab.y);
    vec3 diffuse = environmentIrradiance(N) * baseColor * (1.0 - metallic);
    return (diffuse + mix(dielectric, metal, metallic)) * occlusion;
}

vec3 shadeMetallicRoughness(vec3 baseColor, float metallic, float roughness, float occlusion,
                            vec3 N, vec3 V) {
    return shadeMetallicRoughnessSpecular(baseColor, metallic, roughness, occlusion, N, V,
                                          vec3(0.04), 1.0);
}
#endif
