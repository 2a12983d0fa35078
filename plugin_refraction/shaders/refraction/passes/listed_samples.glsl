// Samples of a list of pixels (ListedSamples.cpp), a dispatch each sample, over the walk's
// colour, traced as the trace traces them (walk.glsl compiled with LAYER_METHOD 4): the pixels
// the hybrid's walk handed over (walk.frag.glsl, LAYER_METHOD 5: hybrid_trace.comp.glsl), or
// with FRESH_LIST the later samples of the trace's or the hybrid's pixels that take the fresh
// samples (walk_motion.glsl: fresh_samples.comp.glsl). The program of each includes this.
// A list, not the rectangle again: a walk's loops run as long as their longest lane, and a
// listed pixel among others would hold its whole block of lanes through them (a CPU
// rasteriser's 4x4 block, a GPU's warp), and would pay for the rectangle's other pixels.
// The walk left the glass motion this pass reads in the motion image: the layers' motions are
// one storage block past a compute shader's 16 (layers.glsl).
#define GLASS_MOTION_READ
#include "refraction/passes/walk.glsl"
#include "refraction/passes/walk_motion.glsl"

layout(local_size_x = 64) in;
const bool kFreshList = FRESH_LIST != 0; // over the pixels that take the fresh samples
// the walk's colour target
layout(SHADED_FORMAT, binding = OUTPUT_IMAGE_UNIT) uniform image2D uShaded;

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool fresh = kFreshList;
    if (i >= (fresh ? walkFreshPixels : handedOverCount))
        return;
    uint pixel = fresh ? freshPixelList[i] : handedOverWords[handedOverListStart() + i];
    ivec2 p = ivec2(pixel & 0xFFFFu, pixel >> 16);
    Entry e;
    pixelEntry(p, e); // the walk found it
    Walk walk;
    vec4 color = vec4(tracedSample(p, e, walk), 1.0);
    if (uTraceSample > 0) {
        vec4 before = imageLoad(uShaded, p);
        color = vec4(color.rgb + before.rgb, before.a);
    }
    if (writesMotion() && uTraceSample == 0) {
        uvec4 m = glassPixelMotion(p, e, walk, gEndT);
        imageStore(uGlassMotion, p, m);
        if (uFreshSamples > 1 && takesFreshSamples(p, m, color.rgb))
            color = vec4(color.rgb / float(uFreshSamples), freshAlpha());
    }
    imageStore(uShaded, p, color);
}
