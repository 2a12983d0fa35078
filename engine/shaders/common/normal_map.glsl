// Tangent-space normal mapping (glTF normalTexture), in whatever space N and the tangent share.
#ifndef COMMON_NORMAL_MAP_GLSL
#define COMMON_NORMAL_MAP_GLSL

// N: unit surface normal; tangent: xyz tangent, w handedness; texel: the map's value there;
// scale: normalTexture.scale.
vec3 perturbNormal(vec3 N, vec4 tangent, vec3 texel, float scale) {
    vec3 T = normalize(tangent.xyz - N * dot(N, tangent.xyz));
    vec3 B = cross(N, T) * tangent.w;
    vec3 n = texel * 2.0 - 1.0;
    n.xy *= scale;
    return normalize(mat3(T, B, N) * n);
}

vec3 perturbNormal(vec3 N, vec4 tangent, sampler2D normalMap, vec2 uv, float scale) {
    return perturbNormal(N, tangent, texture(normalMap, uv).xyz, scale);
}
#endif
