// One geometry pass for both interfaces: every glass fragment, front- or back-facing, is
// blended with MAX into two RGBA32F targets, so each channel keeps the nearest front or the
// farthest back fragment. Exact depths sit in their own channels; normals and d_N ride in the
// low 10 bits of a depth key (1.0 <= key < 2.0: 13 bits of log depth, then the payload), so
// the fragment that wins the depth also wins the payload.
//   target 0: z back, -z front, -key(front, normal.x), -key(front, normal.y)
//   target 1: key(back, normal.x), key(back, normal.y), -key(front, d_N), unused
// Target 0's red channel is the back-face depth map itself (search.glsl reads .r; no surface is
// negative). Before it, rectangle.comp.glsl finds the screen rectangle of the glass
// (glass_rectangle.glsl), so the full-screen passes after it rasterise only that rectangle.
#ifndef REFRACTION_SURFACES_GLSL
#define REFRACTION_SURFACES_GLSL
#include "common/math.glsl" // octEncode, octDecode

const float kNoSurface = NO_SURFACE; // the clear value: MAX keeps any fragment over it

uniform float uKeyNear;     // log depth range of the keys: near plane ...
uniform float uKeyLogRange; // ... and log2(far / near)

float surfaceKey(float z, uint payload) {
    float t = clamp(log2(max(z, uKeyNear) / uKeyNear) / uKeyLogRange, 0.0, 1.0);
    uint q = min(uint(t * 8192.0), 8191u);
    return uintBitsToFloat(0x3F800000u | (q << 10) | (payload & 1023u));
}

uint keyPayload(float key) {
    return floatBitsToUint(abs(key)) & 1023u;
}

uint quantise10(float x) {
    return uint(round(clamp(x, 0.0, 1.0) * 1023.0));
}

#include "refraction/glass_rectangle.glsl"

vec3 octDecodePayload(float keyX, float keyY) {
    return octDecode(vec2(keyPayload(keyX), keyPayload(keyY)) / 1023.0);
}

#endif
