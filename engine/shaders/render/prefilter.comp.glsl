// Prefiltered environment: one mip level of GGX-convolved radiance (roughness = level / (levels-1)),
// by importance sampling the source's mip chain (sample lod from the sample's pdf).
#include "common/math.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = OUTPUT_IMAGE_UNIT) uniform writeonly image2D uTarget;
layout(binding = SOURCE_UNIT) uniform sampler2D uSource;
uniform float uRoughness;
uniform int uSampleCount;

vec3 importanceSampleGgx(vec2 xi, float alpha, vec3 N) {
    float phi = 2.0 * PI * xi.x;
    float cosTheta = sqrt((1.0 - xi.y) / (1.0 + (alpha * alpha - 1.0) * xi.y));
    float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
    vec3 H = vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
    vec3 up = abs(N.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    return normalize(T * H.x + B * H.y + N * H.z);
}

void main() {
    ivec2 size = imageSize(uTarget);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, size)))
        return;
    vec3 N = equirectDirection((vec2(texel) + 0.5) / vec2(size));
    float alpha = max(uRoughness * uRoughness, 1e-4);
    vec2 sourceSize = vec2(textureSize(uSource, 0));
    float texelSolidAngle = 4.0 * PI / (sourceSize.x * sourceSize.y);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int i = 0; i < uSampleCount; ++i) {
        vec3 H = importanceSampleGgx(hammersley(uint(i), uint(uSampleCount)), alpha, N);
        vec3 L = reflect(-N, H);
        float NoL = dot(N, L);
        if (NoL <= 0.0)
            continue;
        float NoH = max(dot(N, H), 0.0);
        float d = (NoH * NoH) * (alpha * alpha - 1.0) + 1.0;
        float D = alpha * alpha / (PI * d * d);
        float pdf = D / 4.0; // D * NoH / (4 VoH), with V = N
        float sampleSolidAngle = 1.0 / (float(uSampleCount) * pdf + 1e-6);
        float lod = max(0.5 * log2(sampleSolidAngle / texelSolidAngle) + 1.0, 0.0);
        sum += textureLod(uSource, equirectUv(L), lod).rgb * NoL;
        weight += NoL;
    }
    imageStore(uTarget, texel, vec4(sum / max(weight, 1e-6), 1.0));
}
