// The glass's extent this frame (GlassRectangleGpu in GpuState.h), reset before the geometry
// pass and grown by rectangle.comp.glsl from the deformed cages: its pixel rectangle
// (inclusive; empty while min > max), which the full-screen passes rasterise instead of the
// screen, and its view-space box (floats as ordered ints); then the walk's count of pixels
// holding more than K layers (LayerStats::overflowPixels); for the papers' search over the
// pair capture, the depth range of its back and front surfaces (resolve.frag.glsl; positive
// floats' bits, whose unsigned order is theirs); the trace's counts (LayerStats).
#ifndef REFRACTION_GLASS_RECTANGLE_GLSL
#define REFRACTION_GLASS_RECTANGLE_GLSL

layout(std430, binding = GLASS_RECTANGLE_BINDING) buffer GlassRectangle {
    int glassPixelMin[2], glassPixelMax[2];
    int glassBoxMin[3], glassBoxMax[3];
    uint glassOverflowPixels;
    uint glassBackRange[2]; // nearest, farthest back depth (0: none)
    uint glassFrontMin;     // nearest front depth (FLT_MAX: none)
    // The trace's rays, BVH nodes visited (low, high word) and the most one pixel's ray visited
    // in one draw.
    uint glassTraceRays, glassTraceSteps[2], glassTraceMaxSteps;
    // The glass pixels walked, and those the hybrid traced: all, and for each of its reasons.
    uint glassWalkedPixels, glassHybridTraced, glassHybridBy[4];
};

#endif
