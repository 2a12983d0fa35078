// One geometry pass for both interfaces: every glass fragment, front- or back-facing, is
// blended with MAX into two RGBA32F targets, so each channel keeps the nearest front or the
// farthest back fragment. Exact depths sit in their own channels; normals and d_N ride in the
// low 10 bits of a depth key (1.0 <= key < 2.0: 13 bits of log depth, then the payload), so
// the fragment that wins the depth also wins the payload.
//   target 0: z back, -z front, -key(front, normal.x), -key(front, normal.y)
//   target 1: key(back, normal.x), key(back, normal.y), -key(front, d_N), unused
// d_N: depth_codes.glsl's 10-bit code. pair_resolve.frag.glsl decodes them.
#ifndef REFRACTION_PAIR_GATHER_GLSL
#define REFRACTION_PAIR_GATHER_GLSL
#include "common/math.glsl" // octEncode, octDecode
#include "refraction/depth_codes.glsl"

const float kNoSurface = NO_SURFACE; // the clear value: MAX keeps any fragment over it

float surfaceKey(float z, uint payload) {
    uint q = min(uint(logDepthFraction(z) * 8192.0), 8191u);
    return uintBitsToFloat(0x3F800000u | (q << 10) | (payload & 1023u));
}

// d_N's code in a key's 10 bits (depth_codes.glsl).
const float kGatheredDistanceLevels = 1022.0;

uint keyPayload(float key) {
    return floatBitsToUint(abs(key)) & 1023u;
}

uint quantise10(float x) {
    return uint(round(clamp(x, 0.0, 1.0) * 1023.0));
}

vec3 octDecodePayload(float keyX, float keyY) {
    return octDecode(vec2(keyPayload(keyX), keyPayload(keyY)) / 1023.0);
}

#endif
