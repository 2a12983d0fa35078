// `refraction.fresh_samples`: the later samples of the trace's or the hybrid's pixels that take
// the fresh samples (walk_motion.glsl), traced, a dispatch each sample (listed_samples.glsl).
#define FRESH_LIST 1
#include "refraction/passes/listed_samples.glsl"
