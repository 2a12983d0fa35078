// What the walk and the hybrid's trace count this frame (WalkCountersGpu in GpuState.h), read
// back on the CPU as LayerStats: the pixels holding more than K layers; the trace's rays, the
// BVH nodes they visited (low, high word) and the most one pixel's ray visited in one draw; the
// glass pixels walked, and those the hybrid traced: all, and for each of its reasons (HYBRID_*:
// bit k counts in walkHybridBy[k]); those that take the fresh samples (walk_motion.glsl), the
// work groups of 64 of the fresh samples' pass over them (an indirect dispatch:
// fresh_samples.comp.glsl) and their list (x | y << 16), which the buffer holds where the frame
// takes fresh samples.
#ifndef REFRACTION_WALK_COUNTERS_GLSL
#define REFRACTION_WALK_COUNTERS_GLSL

layout(std430, binding = WALK_COUNTERS_BINDING) buffer WalkCounters {
    uint walkOverflowPixels;
    uint walkTraceRays, walkTraceSteps[2], walkTraceMaxSteps;
    uint walkedPixels, walkHybridTraced, walkHybridBy[4];
    uint walkFreshPixels, freshGroups[3];
    uint freshPixelList[];
};

#endif
