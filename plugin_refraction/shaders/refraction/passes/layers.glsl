// Every glass surface a pixel's primary ray crosses, captured in one geometry pass
// (layer_capture.frag.glsl) into fixed per-pixel arrays of K fragments, in the order the
// rasteriser produced them (unsorted):
//   LayerHeads  planes of P words (P = pixels): [pixel] the fragment count (may exceed K:
//               overflow); then the overflow fallback's nearest front (atomicMin) and
//               farthest back (atomicMax), each its key and, with textured glass, its surface
//               in three more words (fallbackIndex): every word an atomic bid, so the winner
//               does not depend on the order fragments arrive in; then the list of the pixels
//               that overflowed (overflowIndex), for the kept layers' bids
//   LayerDepths per pixel, ceil(K / 4) vec4: the linear view depth of the fragment in each slot
//               (the search reads four at once)
//   LayerAttrs  per pixel and slot: x the outward view normal (octahedral, 16 + 16 bits);
//               y glass id (bits 0-7, an entry of GlassMaterials), front-facing (bit 8),
//               d_N relative to the depth (bits 16-31, 0: none)
//   LayerMotions (frames that accumulate, else unused) per pixel and slot: the motion of the
//               glass surface there in pixels (common/motion.glsl; two halves)
//   LayerSurfaces (frames with textured glass, GLASS_TEXTURES) per pixel and slot: the glass
//               surface there (GlassSurface: its material's factors times its textures,
//               packSurface's 64 bits)
// A pixel with more than K fragments keeps only its nearest front and farthest back surface
// (the two-surface model, never a partial list): see storedDepths. The pair capture
// (pair_resolve.frag.glsl) fills the same arrays at K = 2, its front as layer 0, its back as layer 1.
#ifndef REFRACTION_LAYERS_GLSL
#define REFRACTION_LAYERS_GLSL
#include "refraction/model/glass_materials.glsl"
#include "common/math.glsl" // octEncode, octDecode
#include "refraction/depth_codes.glsl"
#include "refraction/view.glsl"

// K (layer-capacity) is compiled in (LAYER_CAPACITY, 1-8): every loop over a pixel's layers has
// a constant bound and unrolls.
#ifndef LAYER_CAPACITY
#define LAYER_CAPACITY 4
#endif
const int kLayerCapacity = LAYER_CAPACITY;
const int kDepthGroups = (LAYER_CAPACITY + 3) / 4;
uniform int uPixelCount;    // P: width x height
uniform int uViewportWidth;

layout(std430, binding = LAYER_HEADS_BINDING) coherent buffer LayerHeads { uint layerHeads[]; };
#ifndef LAYER_DEPTH_MAPS // (the walk reads the maps: one storage block fewer, of 16)
layout(std430, binding = LAYER_DEPTHS_BINDING) coherent buffer LayerDepths { vec4 layerDepth4[]; };
#endif
layout(std430, binding = LAYER_ATTRS_BINDING) coherent buffer LayerAttrs { uvec2 layerAttr[]; };

const uint kLayerFront = LAYER_FRONT_BIT;

#ifndef GLASS_MOTION_READ // (the hybrid's trace pass reads no layer's motion: walk_motion.glsl)
layout(std430, binding = LAYER_MOTIONS_BINDING) coherent buffer LayerMotions { uint layerMotion[]; };
#endif

#ifndef GLASS_TEXTURES
#define GLASS_TEXTURES 0
#endif
#if GLASS_TEXTURES
layout(std430, binding = LAYER_SURFACES_BINDING) coherent buffer LayerSurfaces {
    uvec2 layerSurface[];
};
#endif

uint packOctNormal(vec3 n) {
    return packUnorm2x16(octEncode(n));
}

vec3 unpackOctNormal(uint bits) {
    return octDecode(unpackUnorm2x16(bits));
}

// The overflow fallback's keys: 16 bits of log depth, then the glass id (8 bits) and an
// octahedral normal in 4 + 4 bits (coarse, only for overflowing pixels). Unsigned order is
// depth order. With textured glass the surface follows in three more bids, each the key's
// depth over 16 bits of packSurface's 48: every word is won by the nearest (farthest) depth,
// whatever the order, and fragments within one depth step of each other are one surface to
// the fallback (each word the least, or greatest, of theirs).
#if GLASS_TEXTURES
const uint kFallbackWords = 1u + uint(FALLBACK_SURFACE_WORDS);
#else
const uint kFallbackWords = 1u;
#endif

// Where word w (0 the key, 1-3 the surface) of the fallback's layer i (0 the nearest front, 1
// the farthest back) of a pixel is bid for.
uint fallbackIndex(uint pixel, int i, uint w) {
    return uint(uPixelCount) * (1u + uint(i) * kFallbackWords + w) + pixel;
}

// One fragment's bid for every word of its side of the fallback.
void bidForFallback(uint pixel, bool front, uint key, uvec2 surface) {
    int i = front ? 0 : 1;
    uint words[4] = uint[4](key, surface.x & 0xFFFFu, surface.x >> 16, surface.y & 0xFFFFu);
    for (uint w = 0u; w < kFallbackWords; ++w) {
        uint bid = w == 0u ? key : (key & 0xFFFF0000u) | words[w];
        if (front)
            atomicMin(layerHeads[fallbackIndex(pixel, i, w)], bid);
        else
            atomicMax(layerHeads[fallbackIndex(pixel, i, w)], bid);
    }
}

#if GLASS_TEXTURES
// The surface the fallback's layer i of a pixel won.
uvec2 fallbackSurface(uint pixel, int i) {
    uint lo = layerHeads[fallbackIndex(pixel, i, 1u)] & 0xFFFFu;
    uint mid = layerHeads[fallbackIndex(pixel, i, 2u)] & 0xFFFFu;
    return uvec2(lo | (mid << 16), layerHeads[fallbackIndex(pixel, i, 3u)] & 0xFFFFu);
}
#endif

// Word w of the list of the pixels that overflowed, after the heads' planes: 0 their count, 1-3
// the work groups of 64 that bid for their kept layers (an indirect dispatch), then the pixels.
uint overflowIndex(uint w) {
    return uint(uPixelCount) * (1u + 2u * kFallbackWords) + w;
}

// Pixel `pixel`, which just overflowed (its fragment took slot K), into that list.
void listOverflow(uint pixel) {
    uint n = atomicAdd(layerHeads[overflowIndex(0u)], 1u);
    layerHeads[overflowIndex(4u + n)] = pixel;
    if (n % 64u == 0u)
        atomicAdd(layerHeads[overflowIndex(1u)], 1u);
}

// The key of a fragment at depth z, its normal as a layer packs it (packOctNormal), glass id.
uint fallbackKey(float z, uint octNormal, uint id) {
    uint q = min(uint(logDepthFraction(z) * 65536.0), 65535u);
    uvec2 o = uvec2(round(unpackUnorm2x16(octNormal) * 15.0));
    return (q << 16) | ((id & 255u) << 8) | (o.x << 4) | o.y;
}

float fallbackDepth(uint key) {
    return depthAtLogFraction((float(key >> 16) + 0.5) / 65536.0);
}

vec3 fallbackNormal(uint key) {
    return octDecode(vec2(float((key >> 4) & 15u), float(key & 15u)) / 15.0);
}

uint pixelIndex(ivec2 p) {
    return uint(p.y * uViewportWidth + p.x);
}

int storedCount(ivec2 p) {
    return int(layerHeads[pixelIndex(p)]);
}

#ifndef LAYER_DEPTH_MAPS
// Depths of stored layers 4g..4g+3 of pixel p, as the walk reads them (3e38 where unused): an
// overflowing pixel's nearest front and farthest back stand in as layers 0 and 1. Read from the
// arrays by the resolve pass; the walk reads its copy in the depth maps (LAYER_DEPTH_MAPS).
vec4 storedDepths(ivec2 p, int g) {
    uint pixel = pixelIndex(p);
    int n = int(layerHeads[pixel]);
    vec4 slots = vec4(float(4 * g)) + vec4(0.0, 1.0, 2.0, 3.0);
    if (n > kLayerCapacity) {
        uint front = layerHeads[fallbackIndex(pixel, 0, 0u)];
        uint back = layerHeads[fallbackIndex(pixel, 1, 0u)];
        vec4 d = vec4(front != 0xFFFFFFFFu ? fallbackDepth(front) : NO_DEPTH,
                      back != 0u ? fallbackDepth(back) : NO_DEPTH, NO_DEPTH, NO_DEPTH);
        return g == 0 ? d : vec4(NO_DEPTH);
    }
    vec4 d = layerDepth4[pixel * uint(kDepthGroups) + uint(g)];
    return mix(vec4(NO_DEPTH), d, vec4(lessThan(slots, vec4(float(n)))));
}

// The kept layers' bids for the fallback of an overflowing pixel, from their slots (the
// fragments past K bid as the capture draws them): once, after the capture, over the list of
// the pixels that overflowed (layer_overflow.comp.glsl), so that the fragments a pixel keeps pay
// no atomic bids of their own where it does not overflow.
void bidKeptForFallback(uint pixel) {
    for (int i = 0; i < kLayerCapacity; ++i) {
        uvec2 attr = layerAttr[pixel * uint(kLayerCapacity) + uint(i)];
        float z = layerDepth4[pixel * uint(kDepthGroups) + uint(i / 4)][i % 4];
#if GLASS_TEXTURES
        uvec2 surface = layerSurface[pixel * uint(kLayerCapacity) + uint(i)];
#else
        uvec2 surface = uvec2(0u);
#endif
        bidForFallback(pixel, (attr.y & kLayerFront) != 0u, fallbackKey(z, attr.x, attr.y),
                       surface);
    }
}
#endif

#ifdef LAYER_DEPTH_MAPS
// layers 0-3, 4-7 (layer_depths.frag.glsl)
layout(binding = LAYER_DEPTH_MAPS_UNIT) uniform sampler2D uLayerDepths0;
layout(binding = LAYER_DEPTH_MAPS_UNIT + 1) uniform sampler2D uLayerDepths1;

// The maps as stored: an overflowing pixel's pair negated (layerOverflow).
vec4 storedMap(ivec2 p, int g) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(uViewportSize))))
        return vec4(NO_DEPTH);
    return g == 0 ? texelFetch(uLayerDepths0, p, 0) : texelFetch(uLayerDepths1, p, 0);
}

vec4 layerDepths(ivec2 p, int g) {
    return abs(storedMap(p, g));
}
#else
vec4 layerDepths(ivec2 p, int g) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(uViewportSize))))
        return vec4(NO_DEPTH);
    return storedDepths(p, g);
}

// What the maps would store, read from the arrays (the pair's searches ask for it).
vec4 storedMap(ivec2 p, int g) {
    vec4 d = layerDepths(p, g);
    bool overflow = d.x < NO_DEPTH && int(layerHeads[pixelIndex(p)]) > kLayerCapacity;
    return g == 0 && overflow ? vec4(-d.xy, d.zw) : d;
}
#endif

// Layer i of pixel p (see layerDepths), `overflow` if the pixel overflowed.
uvec2 layerAttrOf(ivec2 p, int i, bool overflow) {
    uint pixel = pixelIndex(p);
    if (overflow) {
        uint key = layerHeads[fallbackIndex(pixel, i, 0u)];
        return uvec2(packOctNormal(fallbackNormal(key)), ((key >> 8) & 255u) | (i == 0 ? kLayerFront : 0u));
    }
    return layerAttr[pixel * uint(kLayerCapacity) + uint(i)];
}

bool layerOverflow(ivec2 p) {
#ifdef LAYER_DEPTH_MAPS
    return storedMap(p, 0).x < 0.0;
#else
    return int(layerHeads[pixelIndex(p)]) > kLayerCapacity;
#endif
}

uvec2 layerAttrAt(ivec2 p, int i) {
    return layerAttrOf(p, i, layerOverflow(p));
}

const int kDepthSlots = 4 * kDepthGroups;

// Pixel p's layers as every scan over them reads them: each slot's depth (UNUSED_DEPTH and up
// where unused; all unused off screen) and whether the pixel overflowed (its nearest front and
// farthest back then stand in as layers 0 and 1: layerAttrOf).
struct PixelLayers {
    vec4 depths[kDepthGroups]; // slots 4g..4g+3
    bool overflow;
};

float layerDepth(PixelLayers l, int i) {
    return l.depths[i / 4][i % 4];
}

PixelLayers pixelLayers(ivec2 p) {
    PixelLayers l;
    l.overflow = false;
    for (int g = 0; g < kDepthGroups; ++g) {
#ifdef LAYER_DEPTH_MAPS
        vec4 stored = storedMap(p, g);
        l.overflow = l.overflow || (g == 0 && stored.x < 0.0);
        l.depths[g] = abs(stored);
#else
        l.depths[g] = layerDepths(p, g);
#endif
    }
#ifndef LAYER_DEPTH_MAPS
    l.overflow = layerOverflow(p);
#endif
    return l;
}

// Whether a ray that went from depth zFrom to depth z, now in pixel p, is still in a segment of
// layer parity `parity`: none of p's layers lies between the two depths (a ray along the line
// of sight crosses surfaces within one pixel), and the number of p's layers in front of z has
// that parity (a ray coming in from the side). Off screen: no layers.
bool inSegment(ivec2 p, float zFrom, float z, int parity) {
    float lo = min(zFrom, z), hi = max(zFrom, z);
    PixelLayers l = pixelLayers(p);
    int count = 0;
    bool between = false;
    for (int g = 0; g < kDepthGroups; ++g) { // four slots at once
        vec4 d = l.depths[g];
        count += int(dot(vec4(lessThan(d, vec4(z))), vec4(1.0)));
        between = between || any(bvec4(vec4(greaterThan(d, vec4(lo))) * vec4(lessThan(d, vec4(hi)))));
    }
    return !between && (count & 1) == parity;
}

// The glass surface of layer i of pixel p (its attributes `attr`): as the capture stored it
// where the frame's glass is textured (for an overflowing pixel, its fallback's), else its
// material's.
GlassSurface layerSurfaceOf(ivec2 p, int i, uvec2 attr, bool overflow) {
#if GLASS_TEXTURES && !defined(SKIP_SURFACES) // glass-bench --skip surfaces: the material's
    if (overflow && (i == 0 || i == 1))
        return unpackSurface(fallbackSurface(pixelIndex(p), i));
    if (!overflow && i >= 0)
        return unpackSurface(layerSurface[pixelIndex(p) * uint(kLayerCapacity) + uint(i)]);
#endif
    return materialSurface(glassMaterials[attr.y & 255u]);
}

uint layerGlass(uvec2 attr) {
    return attr.y & 255u;
}

bool layerFront(uvec2 attr) {
    return (attr.y & kLayerFront) != 0u;
}

vec3 layerNormal(uvec2 attr) {
    return unpackOctNormal(attr.x);
}

// d_N in view units at depth z, -1 where none was measured (depth_codes.glsl's 16-bit code).
const float kLayerDistanceLevels = 65534.0;
float layerNormalDistance(uvec2 attr, float z) {
    return normalDistanceOf(attr.y >> 16, z, kLayerDistanceLevels);
}

#endif
