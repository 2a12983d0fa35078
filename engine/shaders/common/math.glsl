// Constants and small helpers shared by the engine's shaders.
#ifndef COMMON_MATH_GLSL
#define COMMON_MATH_GLSL
const float PI = 3.14159265358979;

// Equirectangular mapping: direction -> uv (u along longitude from -z, v = 0 looking up +y).
vec2 equirectUv(vec3 d) {
    d = normalize(d);
    float u = 0.5 + atan(d.x, -d.z) / (2.0 * PI);
    float v = acos(clamp(d.y, -1.0, 1.0)) / PI;
    return vec2(u, v);
}

vec3 equirectDirection(vec2 uv) {
    float phi = (uv.x - 0.5) * 2.0 * PI;
    float theta = uv.y * PI;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

// Low-discrepancy 2D point i of n (Hammersley).
vec2 hammersley(uint i, uint n) {
    uint bits = bitfieldReverse(i);
    return vec2(float(i) / float(n), float(bits) * 2.3283064365386963e-10);
}
#endif
