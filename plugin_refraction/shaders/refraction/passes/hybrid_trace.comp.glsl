// `refraction.hybrid_trace`: the pixels the hybrid's walk handed over (walk.frag.glsl), traced
// as the trace traces them, a dispatch each sample (listed_samples.glsl).
#define FRESH_LIST 0
#include "refraction/passes/listed_samples.glsl"
