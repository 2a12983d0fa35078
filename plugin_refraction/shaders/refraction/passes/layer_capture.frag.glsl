// The layered path's one geometry pass: every glass fragment, front- or back-facing, appends
// itself to its pixel's fixed array (layers.glsl): depth, outward normal after normal mapping,
// glass id, facing, d_N. Glass behind the opaque scene is kept too (a glass head's far side
// behind its opaque eyes, which rays inside the head still cross); the shading pass skips pixels
// whose nearest glass is hidden. Fragments past K only count, and bid for the pixel's overflow
// fallback (nearest front, farthest back; the kept ones bid from their slots after the pass, over
// the list of the pixels that overflowed). The depth attachment (depth test ALWAYS) is the
// shading pass's mask: below 1 where any glass was kept. With textured glass in the frame
// (GLASS_TEXTURES), each kept fragment's surface too, and the fallback's; where the frame
// accumulates, each kept fragment's motion. Nothing depends on the order the fragments of a
// pixel arrive in: slots are taken by one atomic, the fallback is won by atomic bids over all.
#include "common/motion.glsl"
#include "refraction/passes/fragment_surface.glsl"
#include "refraction/view.glsl"
#include "refraction/passes/layers.glsl"

uniform int uGlassId;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint pixel = pixelIndex(p);
    float z = -vViewPosition.z;
    vec3 n = fragmentNormal();
    uint id = uint(uGlassId);
    uint d = normalDistanceCode(vNormalDistance, z, kLayerDistanceLevels);
    uint slot = atomicAdd(layerHeads[pixel], 1u);
#if GLASS_TEXTURES
    // Read by every fragment, kept or not: its textures' filtering needs the derivatives of
    // uniform control flow.
    uvec2 surface = packSurface(fragmentSurface(id));
#else
    uvec2 surface = uvec2(0u);
#endif
    if (slot < uint(kLayerCapacity)) {
        layerDepth4[pixel * uint(kDepthGroups) + slot / 4u][slot % 4u] = z;
        layerAttr[pixel * uint(kLayerCapacity) + slot] =
            uvec2(packOctNormal(n), id | (gl_FrontFacing ? kLayerFront : 0u) | (d << 16));
#if GLASS_TEXTURES
        layerSurface[pixel * uint(kLayerCapacity) + slot] = surface;
#endif
        if (writesMotion())
            layerMotion[pixel * uint(kLayerCapacity) + slot] =
                packHalf2x16(clipToPixel(vClip) - clipToPixel(vPreviousClip));
    }
#ifndef SKIP_FALLBACK // glass-bench --skip fallback
    // A fragment past K bids for the fallback: its key, and its surface with it (layers.glsl,
    // bidForFallback). The first lists its pixel, whose kept layers bid from their slots after
    // the pass (layer_overflow.comp.glsl).
    else {
        bidForFallback(pixel, gl_FrontFacing, fallbackKey(z, packOctNormal(n), id), surface);
        if (slot == uint(kLayerCapacity))
            listOverflow(pixel);
    }
#endif
}
