// The depth ranges of the pair capture's surfaces (PairRangesGpu in GpuState.h), which the
// papers' search over the pair marches between: written by the pair's resolve
// (resolve.frag.glsl) as positive floats' bits, whose unsigned order is theirs.
#ifndef REFRACTION_PAIR_RANGES_GLSL
#define REFRACTION_PAIR_RANGES_GLSL

layout(std430, binding = PAIR_RANGES_BINDING) buffer PairRanges {
    uint pairBackRange[2]; // nearest, farthest back depth (0: none)
    uint pairFrontMin;     // nearest front depth (FLT_MAX: none)
};

#endif
