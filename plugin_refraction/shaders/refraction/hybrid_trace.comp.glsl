// The hybrid's trace pass: the pixels its walk handed over (walk.frag.glsl, LAYER_METHOD 5)
// traced as the trace traces them (walk.glsl compiled with LAYER_METHOD 4), a dispatch each
// trace sample, over the walk's colour. A list, not the rectangle again: the trace's loops run
// as long as their longest lane, and a handed-over pixel among walked ones would hold its
// whole block of lanes through them (a CPU rasteriser's 4x4 block, a GPU's warp).
// The walk left the glass motion this pass reads in the motion image: the layers' motions are
// one storage block past a compute shader's 16 (layers.glsl).
#define GLASS_MOTION_READ
#include "refraction/walk.glsl"
#include "refraction/walk_motion.glsl"

layout(local_size_x = 64) in;
// the walk's colour target
layout(SHADED_FORMAT, binding = OUTPUT_IMAGE_UNIT) uniform image2D uShaded;

void main() {
    if (gl_GlobalInvocationID.x >= handedOverCount)
        return;
    uint pixel = handedOverWords[handedOverListStart() + gl_GlobalInvocationID.x];
    ivec2 p = ivec2(pixel & 0xFFFFu, pixel >> 16);
    Entry e;
    pixelEntry(p, e); // the walk found it
    Walk walk;
    vec3 color = tracedSample(p, e, walk);
    if (uTraceSample > 0)
        color += imageLoad(uShaded, p).rgb;
    imageStore(uShaded, p, vec4(color, 1.0));
    if (uWriteMotion != 0 && uTraceSample == 0)
        imageStore(uGlassMotion, p, glassPixelMotion(p, e, walk, gEndT));
}
