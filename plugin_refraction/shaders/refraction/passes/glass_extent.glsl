// The glass's extent this frame (GlassExtentGpu in GpuState.h), reset and grown by the
// glass_extent pass (glass_extent.comp.glsl) from the deformed cages before any capture: its
// pixel rectangle (inclusive; empty while min > max), which the full-screen passes rasterise
// instead of the screen (rectangle.vert.glsl), and its view-space box (floats as ordered ints),
// where the walk's searches end.
#ifndef REFRACTION_GLASS_EXTENT_GLSL
#define REFRACTION_GLASS_EXTENT_GLSL
#include "refraction/ordered.glsl"

layout(std430, binding = GLASS_EXTENT_BINDING) buffer GlassExtent {
    int glassPixelMin[2], glassPixelMax[2];
    int glassBoxMin[3], glassBoxMax[3];
};

// The view-space box of every glass vertex this frame.
void glassBox(out vec3 lo, out vec3 hi) {
    lo = vec3(orderedToFloat(glassBoxMin[0]), orderedToFloat(glassBoxMin[1]),
              orderedToFloat(glassBoxMin[2]));
    hi = vec3(orderedToFloat(glassBoxMax[0]), orderedToFloat(glassBoxMax[1]),
              orderedToFloat(glassBoxMax[2]));
}

#endif
