// Depth range of the valid texels of a surface depth map (DIR §3, pass 2): per 16x16 tile a
// shared-memory reduction, then one atomic min and max per tile. Positive floats order like
// their bit patterns, so the atomics work on uints.
layout(local_size_x = 16, local_size_y = 16) in;

uniform sampler2D uDepth;
uniform int uSlot; // 0: back map, 1: front map
layout(std430, binding = 0) buffer Range { uint range[]; }; // [slot*2] min bits, [slot*2+1] max bits

shared float sMin[256];
shared float sMax[256];

void main() {
    ivec2 size = textureSize(uDepth, 0);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    float d = all(lessThan(texel, size)) ? texelFetch(uDepth, texel, 0).r : 0.0;
    uint i = gl_LocalInvocationIndex;
    sMin[i] = d > 0.0 ? d : 3.0e38;
    sMax[i] = d > 0.0 ? d : 0.0;
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
