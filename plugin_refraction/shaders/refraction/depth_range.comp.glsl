// Depth range of the valid texels of a surface depth map (DIR §3, pass 2): each thread scans a
// 4x4 block, a 16x16 group reduces its 64x64 tile in shared memory, then one atomic min and
// max per tile. Positive floats order like their bit patterns, so the atomics work on uints.
layout(local_size_x = 16, local_size_y = 16) in;

uniform sampler2D uDepth;
uniform int uSlot; // 0: back map, 1: front map
layout(std430, binding = 0) buffer Range { uint range[]; }; // [slot*2] min bits, [slot*2+1] max bits
#include "refraction/glass_rectangle.glsl" // texels outside its rectangle hold no surface

shared float sMin[256];
shared float sMax[256];

void main() {
    ivec2 size = textureSize(uDepth, 0);
    ivec2 base = ivec2(gl_GlobalInvocationID.xy) * 4;
    float lo = 3.0e38, hi = 0.0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            ivec2 texel = base + ivec2(x, y);
            bool inside = all(lessThan(texel, size)) &&
                          all(greaterThanEqual(texel, ivec2(glassPixelMin[0], glassPixelMin[1]))) &&
                          all(lessThanEqual(texel, ivec2(glassPixelMax[0], glassPixelMax[1])));
            float d = inside ? texelFetch(uDepth, texel, 0).r : 0.0;
            if (d > 0.0) {
                lo = min(lo, d);
                hi = max(hi, d);
            }
        }
    uint i = gl_LocalInvocationIndex;
    sMin[i] = lo;
    sMax[i] = hi;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1u) {
        if (i < stride) {
            sMin[i] = min(sMin[i], sMin[i + stride]);
            sMax[i] = max(sMax[i], sMax[i + stride]);
        }
        barrier();
    }
    if (i == 0u && sMax[0] > 0.0) {
        atomicMin(range[2 * uSlot], floatBitsToUint(sMin[0]));
        atomicMax(range[2 * uSlot + 1], floatBitsToUint(sMax[0]));
    }
}
