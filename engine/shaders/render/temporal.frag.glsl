// `temporal`: this frame's colour (its projection jittered under the pixel) blended into the
// history the renderer keeps, each pixel reprojected by its motion (common/motion.glsl; a path
// through glass first where the glass it entered was, then where its end was). The history is
// reused where it shows what the pixel, or a neighbour (its footprint), tracks now: the same
// kind and object, no depth jump (disocclusion), no jump in the direction a path through glass
// left it. While anything moves it is read with a Catmull-Rom filter, clipped toward the mean
// of the frame's 3x3 neighbourhood to 0.75 of its deviation (variance clipping in YCoCg) and
// weighted uHistoryWeight (1 - 1/n over its first n frames); while nothing moves (uStill) it is
// read where it lies, unclipped, and every frame weighs the same: N still frames average to N
// samples of one frame. A pixel whose colour's alpha is -k holds the mean of k samples (a
// plugin's fresh samples) and weighs k frames' samples, against the history's samples.
// Compiled in (a variant each, Renderer::selectPrograms; a CPU rasteriser runs every branch):
// TEMPORAL_STILL, a frame where nothing moved; TEMPORAL_REJECT, the history's checks and
// clipping (TemporalSettings::rejectHistory); TEMPORAL_VIEW, the debug view shown (0: none).
#include "common/motion.glsl"

#ifndef TEMPORAL_STILL
#define TEMPORAL_STILL 0
#endif
#ifndef TEMPORAL_REJECT
#define TEMPORAL_REJECT 1
#endif
#ifndef TEMPORAL_VIEW
#define TEMPORAL_VIEW 0
#endif

layout(binding = SOURCE_UNIT) uniform sampler2D uColor;
layout(binding = MOTION_UNIT) uniform usampler2D uMotion;
layout(binding = HISTORY_UNIT) uniform sampler2D uHistoryColor; // rgb; a: the frames it holds
layout(binding = HISTORY_UNIT + 1) uniform usampler2D uHistoryMotion;

uniform int uIndex; // the frame's index in the history: 0, none to reuse
uniform float uHistoryWeight;

layout(location = 0) out vec4 outColor;
#if TEMPORAL_VIEW
layout(location = 1) out vec4 outView;
#endif

vec3 toYCoCg(vec3 c) {
    return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b,
                -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}

vec3 fromYCoCg(vec3 c) {
    return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

// The history's colour at `pos` (pixels) under a Catmull-Rom filter, as five bilinear reads.
vec3 historyCatmullRom(vec2 pos) {
    vec2 size = vec2(textureSize(uHistoryColor, 0));
    vec2 t = floor(pos - 0.5) + 0.5, f = pos - t;
    vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    vec2 w3 = f * f * (-0.5 + 0.5 * f);
    vec2 w12 = w1 + w2;
    vec2 p0 = (t - 1.0) / size, p3 = (t + 2.0) / size, p12 = (t + w2 / w12) / size;
    float a = w12.x * w0.y, b = w0.x * w12.y, c = w12.x * w12.y, d = w3.x * w12.y, e = w12.x * w3.y;
    vec3 sum = textureLod(uHistoryColor, vec2(p12.x, p0.y), 0.0).rgb * a +
               textureLod(uHistoryColor, vec2(p0.x, p12.y), 0.0).rgb * b +
               textureLod(uHistoryColor, p12, 0.0).rgb * c +
               textureLod(uHistoryColor, vec2(p3.x, p12.y), 0.0).rgb * d +
               textureLod(uHistoryColor, vec2(p12.x, p3.y), 0.0).rgb * e;
    return max(sum / (a + b + c + d + e), vec3(0.0));
}

// Whether the history texel `h` shows what pixel p, or a neighbour, tracks now (the pixel's
// footprint spans them: one jittered sample a frame may see its neighbour's surface, or leave
// curved glass in another direction, without the history being stale).
bool seenAround(ivec2 p, uvec4 m, uvec4 h) {
    if (showsSame(m, h))
        return true;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 q = p + ivec2(x, y);
            if ((x != 0 || y != 0) && all(greaterThanEqual(q, ivec2(0))) &&
                all(lessThan(q, ivec2(uMotionSize))) && showsSame(texelFetch(uMotion, q, 0), h))
                return true;
        }
    return false;
}

vec3 motionColor(vec2 motion) {
    float len = length(motion);
    float hue = atan(motion.y, motion.x) / (2.0 * PI) + 0.5;
    vec3 rgb = clamp(abs(fract(hue + vec3(0.0, 2.0, 1.0) / 3.0) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
    return rgb * min(len / 8.0, 1.0);
}

// The history's colour for a pixel whose history is kept, at `previous` (its texel hp) while
// anything moves, toward the mean of the frame's 3x3 neighbourhood around p (`clipped`: far
// out of it).
vec3 movingHistory(ivec2 p, vec2 previous, out bool clipped) {
    clipped = false;
#ifdef SKIP_HISTORY_FILTER // glass-bench --skip history_filter: one bilinear read
    vec2 size = vec2(textureSize(uHistoryColor, 0));
    vec3 history = textureLod(uHistoryColor, previous / size, 0.0).rgb;
#else
    vec3 history = historyCatmullRom(previous);
#endif
#if TEMPORAL_REJECT && !defined(SKIP_CLIP) // variance clipping toward the neighbourhood's mean
    vec3 mean = vec3(0.0), square = vec3(0.0);
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 q = clamp(p + ivec2(x, y), ivec2(0), ivec2(uMotionSize) - 1);
            vec3 c = toYCoCg(texelFetch(uColor, q, 0).rgb);
            mean += c;
            square += c * c;
        }
    mean /= 9.0;
    vec3 sigma = sqrt(max(square / 9.0 - mean * mean, vec3(0.0)));
    vec3 h = toYCoCg(history), offset = h - mean;
    vec3 extent = 0.75 * sigma + 1e-4;
    vec3 units = abs(offset / extent);
    float outside = max(units.x, max(units.y, units.z));
    if (outside > 1.0) {
        history = max(fromYCoCg(mean + offset / outside), vec3(0.0));
        clipped = outside > 1.5;
    }
#endif
    return history;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 source = texelFetch(uColor, p, 0);
    vec3 color = source.rgb;
    if (any(isnan(color)) || any(isinf(color)))
        color = vec3(0.0);
    float samples = source.a < 0.0 ? -source.a : 1.0;
    uvec4 m = texelFetch(uMotion, p, 0);
    vec2 candidates[2];
    int count = motionCandidates(m, vec2(p) + 0.5, candidates);
    // Nothing moved: the history is this frame's own, whatever one sample a pixel showed.
    bool kept = false;
    vec2 previous = vec2(p) + 0.5, motion = candidates[0];
    ivec2 hp = p;
    for (int i = 0; i < count && !kept && uIndex > 0; ++i) {
        motion = candidates[i];
        previous = vec2(p) + 0.5 - motion;
        hp = ivec2(floor(previous));
        kept = all(greaterThanEqual(hp, ivec2(0))) && all(lessThan(hp, ivec2(uMotionSize)));
#if !TEMPORAL_STILL && TEMPORAL_REJECT
#ifdef SKIP_FOOTPRINT // glass-bench --skip footprint: the pixel's own motion alone
        kept = kept && showsSame(m, texelFetch(uHistoryMotion, hp, 0));
#else
        kept = kept && seenAround(p, m, texelFetch(uHistoryMotion, hp, 0));
#endif
#endif
    }
    bool clipped = false;
    // The history's alpha: the samples it holds (counted up to the weight's equivalent while
    // anything moves).
    float cap = 1.0 / max(1.0 - uHistoryWeight, 1e-3);
    vec4 result = vec4(color, TEMPORAL_STILL != 0 ? samples : min(samples, cap));
    if (kept) {
        float n = texelFetch(uHistoryColor, hp, 0).a;
#if TEMPORAL_STILL // every sample the same weight: the history is the mean of n
        vec3 history = texelFetch(uHistoryColor, hp, 0).rgb;
        result = vec4(mix(history, color, samples / (n + samples)), n + samples);
#else
        vec3 history = movingHistory(p, previous, clipped);
        // The history weighs as cap - 1 samples would (at most n): one sample takes
        // 1 - uHistoryWeight of the result, k samples k / (k + cap - 1).
        float alpha = samples / (samples + min(n, cap - 1.0));
        result = vec4(mix(history, color, alpha), min(n + samples, cap));
#endif
    }
    outColor = result;
#if TEMPORAL_VIEW == TEMPORAL_VIEW_REJECTED
    outView = vec4(!kept ? vec3(1.0, 0.1, 0.1) : clipped ? vec3(0.1, 1.0, 0.1) : vec3(0.3), 1.0);
#elif TEMPORAL_VIEW == TEMPORAL_VIEW_MOTION
    outView = vec4(motionColor(motion), 1.0);
#endif
}
