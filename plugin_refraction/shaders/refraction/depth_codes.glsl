// The depth codes the captures write and the walk reads, one place each:
//   the view depth of a depth-buffer value (the camera's perspective projection);
//   the fraction of the log depth range a view depth lies at, the keys' depth (the pair's
//     MAX-blended keys, pair_gather.glsl, and the layers' overflow fallback, layers.glsl);
//   d_N relative to the depth, in `levels` + 1 steps over [0, 1] after 0 for none (the layers'
//     16 bits, the gathered pair's 10).
#ifndef REFRACTION_DEPTH_CODES_GLSL
#define REFRACTION_DEPTH_CODES_GLSL

uniform float uKeyNear;     // the keys' log depth range: the near plane ...
uniform float uKeyLogRange; // ... and log2(far / near)

float viewDepthOf(float depthBufferValue, float near, float far) {
    float ndc = depthBufferValue * 2.0 - 1.0;
    return 2.0 * near * far / (far + near - ndc * (far - near));
}

float logDepthFraction(float z) {
    return clamp(log2(max(z, uKeyNear) / uKeyNear) / uKeyLogRange, 0.0, 1.0);
}

float depthAtLogFraction(float t) {
    return uKeyNear * exp2(t * uKeyLogRange);
}

uint normalDistanceCode(float normalDistance, float z, float levels) {
    return normalDistance >= 0.0 ? 1u + uint(round(clamp(normalDistance / z, 0.0, 1.0) * levels))
                                 : 0u;
}

float normalDistanceOf(uint code, float z, float levels) {
    return code == 0u ? -1.0 : float(code - 1u) / levels * z;
}

#endif
