// After the capture, over the pixels that overflowed (their list, layers.glsl listOverflow): each
// one's K kept layers bid for its fallback from their slots, as the fragments past K did as they
// were drawn. Between the two, every fragment of the pixel has bid, whatever the order.
#include "refraction/passes/layers.glsl"

layout(local_size_x = 64) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < layerHeads[overflowIndex(0u)])
        bidKeptForFallback(layerHeads[overflowIndex(4u + i)]);
}
