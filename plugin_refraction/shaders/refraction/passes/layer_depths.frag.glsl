// After the capture, over the glass pixels (the mask's early test): each pixel's layer depths
// as the walk reads them (layers.glsl storedDepths: the overflow fallback in place, negated so
// that the map itself says the pixel overflowed; 3e38 where unused) into one or two RGBA32F
// maps, so that a search sample costs one texel fetch.
#include "refraction/passes/layers.glsl"

layout(location = 0) out vec4 outDepths0;
layout(location = 1) out vec4 outDepths1;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    bool overflow = int(layerHeads[pixelIndex(p)]) > kLayerCapacity;
    outDepths0 = storedDepths(p, 0);
    if (overflow)
        outDepths0.xy = -outDepths0.xy;
    outDepths1 = kDepthGroups > 1 ? storedDepths(p, 1) : vec4(NO_DEPTH);
}
