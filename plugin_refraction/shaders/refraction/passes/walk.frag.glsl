// The walk's shading pass (walk.glsl): over the glass rectangle, against the capture's mask, a
// draw each trace sample for the trace and the hybrid, added up; where the frame accumulates,
// one sample, each pixel's motion by what it shows (walk_motion.glsl), and while anything moves
// the pixels whose history will be rejected listed for the fresh samples' pass.
#include "refraction/passes/walk.glsl"
#include "refraction/passes/walk_motion.glsl"

// The mask's depth test before the shader (its overflow count is a side effect, which would
// otherwise move the test after it, for every pixel of the rectangle).
layout(early_fragment_tests) in;
out vec4 outColor;
// The nearest layer for the outline pass (outlines.frag.glsl), packed: its depth (half
// float, bits 0-15), glass id (16-23) and its normal's part along the line of sight (24-31,
// unorm of the absolute value: finest near an outline, where it goes to 0); 0: no glass.
layout(location = 1) out uint outSurface;

#if LAYER_METHOD == METHOD_HYBRID
// Pixel p (its bit `bit`) into the hybrid's list for its trace pass, counted by its reasons.
void handOver(ivec2 p, uvec2 bit, uint reasons) {
    uint slot = atomicAdd(handedOverCount, 1u);
    handedOverWords[handedOverListStart() + slot] = uint(p.x) | uint(p.y) << 16;
    atomicOr(handedOverWords[bit.x], bit.y);
    if (slot % 64u == 0u)
        atomicAdd(handedOverGroups[0], 1u);
    atomicAdd(walkHybridTraced, 1u);
    for (int k = 0; k < 4; ++k)
        if ((reasons & (1u << k)) != 0u) // HYBRID_*: bit k
            atomicAdd(walkHybridBy[k], 1u);
}
#endif

// WALK_DEBUG 0: a variant for frames without a debug view, which leaves it out.
#ifndef WALK_DEBUG
#define WALK_DEBUG 1
#endif

// The debug view's colour for pixel p (uDebug; DEBUG_NONE: `color`, the shaded one), its
// entry e, its walk, its `stored` layers and the hybrid's reasons to trace it.
vec3 debugView(vec3 color, ivec2 p, Entry e, Walk walk, int stored, uint handedOver) {
    vec3 lo, hi; // back-depth and dv over the farthest glass depth of the frame
    glassBox(lo, hi);
    switch (uDebug) {
    case DEBUG_BACK_DEPTH: color = vec3(e.far / max(-lo.z, 1e-6)); break; // the farthest layer
    case DEBUG_BACK_NORMAL: color = layerNormal(layerAttrAt(p, e.farthest)) * 0.5 + 0.5; break;
    case DEBUG_DV: color = vec3((e.far - e.z) / max(-lo.z, 1e-6)); break; // nearest to farthest
    case DEBUG_DN: color = vec3(max(layerNormalDistance(e.attr, e.z), 0.0) / e.z); break;
    case DEBUG_EXIT_UV: color = vec3(projectToUv(walk.firstExit), walk.fallback ? 1.0 : 0.0); break;
    case DEBUG_STEPS:
        color = vec3(float(walk.steps) / float(max(uSteps * (uInterfaces - 1), 1)),
                     walk.fallback ? 1.0 : 0.0, float(walk.path.interfaces) / float(uInterfaces));
        break;
    case DEBUG_TIR: color = walk.tir ? vec3(1.0, 0.0, 0.0) : vec3(0.1); break;
    case DEBUG_EXIT_POINT: color = uViewToWorld * walk.firstExit + uViewOriginWorld; break;
    case DEBUG_EXIT_DIRECTION: color = uViewToWorld * walk.path.dir; break;
    case DEBUG_LAYER_COUNT: // K layers white, fewer grey, overflow red
        color = stored > kLayerCapacity ? vec3(1.0, 0.0, 0.0)
                                        : vec3(float(stored) / float(kLayerCapacity));
        break;
    case DEBUG_OVERFLOW: color = stored > kLayerCapacity ? vec3(1.0, 0.0, 0.0) : vec3(0.1); break;
    case DEBUG_HYBRID: // traced for overflow red, off the layers yellow, TIR blue, an outline green
        color = (handedOver & uint(HYBRID_OVERFLOW)) != 0u      ? vec3(1.0, 0.0, 0.0)
                : (handedOver & uint(HYBRID_LEFT_LAYERS)) != 0u ? vec3(1.0, 1.0, 0.0)
                : (handedOver & uint(HYBRID_REFLECTION)) != 0u  ? vec3(0.0, 0.3, 1.0)
                : (handedOver & uint(HYBRID_OUTLINE)) != 0u     ? vec3(0.0, 1.0, 0.0)
                                                                : vec3(0.1);
        break;
    default: break;
    }
    return color;
}

void main() {
#ifdef SKIP_ENTRY // glass-bench --skip entry: the pass's rectangle and mask alone
    outColor = vec4(0.0, 0.0, 0.0, 1.0);
    outSurface = 0u;
    return;
#endif
    ivec2 p = ivec2(gl_FragCoord.xy);
    Entry e;
    if (!pixelEntry(p, e))
        discard; // no glass, or only glass hidden behind the opaque scene
    vec3 N1 = facingNormal(e);
    outSurface = (packHalf2x16(vec2(e.z, 0.0)) & 0xFFFFu) | (layerGlass(e.attr) << 16) |
                 (uint(round(abs(dot(N1, e.V)) * 255.0)) << 24);
#ifdef SKIP_WALK // glass-bench --skip walk: the entry alone
    outColor = vec4(e.surface.baseColor * abs(N1.z), 1.0);
    return;
#endif
    Walk walk;
    int stored = storedCount(p);
    uint handedOver = 0u; // the hybrid's reasons to trace this pixel (uHybridCriteria's bits)
#if LAYER_METHOD == METHOD_TRACE
    vec3 color = tracedSample(p, e, walk);
#else
#if LAYER_METHOD == METHOD_HYBRID
    uvec2 bit = handedOverBit(p);
    if (uTraceSample > 0 && (handedOverWords[bit.x] & bit.y) != 0u)
        discard; // the first sample handed the pixel over: the trace pass shades it
#endif
    vec3 color = layeredSample(p, e, N1, stored, walk);
#if LAYER_METHOD == METHOD_HYBRID
    // The walk's path where the layers represent it, the trace's where they may not, judged
    // by the first sample from what the walk knows (handedOverBy).
    handedOver = uTraceSample == 0 ? handedOverBy(walk) : 0u;
    if (handedOver != 0u) // for the trace pass, which shades it over this
        handOver(p, bit, handedOver);
#endif
#endif
    if (uTraceSample == 0)
        atomicAdd(walkedPixels, 1u);
    if (stored > kLayerCapacity && uTraceSample == 0)
        atomicAdd(walkOverflowPixels, 1u);
#if WALK_DEBUG
    color = debugView(color, p, e, walk, stored, handedOver);
#endif
    // What the pixel shows, for the temporal resolve, and whether it takes the fresh samples
    // (the hybrid's trace pass records and decides its own pixels').
    float alpha = 1.0;
#ifndef SKIP_MOTION // glass-bench --skip motion
    if (writesMotion() && uTraceSample == 0) {
        uvec4 m = handedOver == 0u ? glassPixelMotion(p, e, walk, gEndT) : handedOverMotion(p, e);
        imageStore(uGlassMotion, p, m);
        if (uFreshSamples > 1 && handedOver == 0u && takesFreshSamples(p, m, color)) {
            color /= float(uFreshSamples);
            alpha = freshAlpha();
        }
    }
#endif
    outColor = vec4(color, alpha);
}
