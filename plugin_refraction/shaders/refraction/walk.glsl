// The walk (walk.frag.glsl, the one shading pass over the glass pixels, and the hybrid's trace
// pass, walk_trace.comp.glsl), whichever capture filled the layers: a pixel's primary ray
// enters the nearest captured layer and walks the others (layers.glsl) in
// texture space, refracting at every interface it crosses (or reflecting under total internal
// reflection) with the media on both sides, up to N interfaces; then it sees the nearby opaque
// scene or the environment (scene_lookup.glsl). An opaque part met between two interfaces
// (inside the glass, or between two pieces) ends the walk there. ARCHITECTURE.md ("How a ray
// walks the layers") has the figure. Compiled in: the capture (CAPTURE_PAIR), K, the method
// (how the walk finds an exit: SIR none, ISR Wyman's estimate, DIR a search, the trace the
// exact hit in the glass BVH, the hybrid DIR's search, handing the pixels it cannot represent
// to the trace pass), the dispersion search and the punctual lights.
//
// Media (the Embree reference's rule too): crossing a glass surface against its outward normal
// enters its glass (a stack of up to four, the newest on top); crossing one along its normal
// leaves the most recent entry of the same solid (a character: the pieces of one character are
// one solid), if the ray is in it at all. The medium is the top of the stack, air when empty;
// where it does not change (overlapping glass, a surface crossed twice in the samples) the ray
// goes straight on.
//
// DIR over the layers generalises the papers' search: the ray from the last crossing is
// sampled in texture space (perspective-correct, coarse samples up to where it leaves the
// glass's view-space box) and, at each sample, the number of layers of that pixel in front of
// the sample's depth is counted. Closed surfaces come in pairs along any line of sight, so the
// count's parity changes only where the ray crosses a surface (a silhouette adds or removes
// two); a layer between two samples' depths in one pixel is a crossing along the line of sight.
// The first sample out of the segment is refined by the conservative binary search (DIR §3.3,
// search-steps halvings) and the layer crossed is the one that pixel's count passed.
//
// Over the pair capture (CAPTURE_PAIR, the papers' two-surface model: layer 0 the nearest
// front, layer 1 the back, resolve.frag.glsl) the walk is the papers' path: one piece of glass
// entered at the front and left at the back, its exit searched in the back depths (DIR §3.2-3.3)
// and, after a total internal reflection toward the camera, in the front ones, the normal there
// read mip-filtered (DIR §3.1); past the pair there is nothing more to cross.
#define LAYER_DEPTH_MAPS // the resolve pass's copy of the depths (layers.glsl)
#include "refraction/glass_surface.glsl"
#include "refraction/layers.glsl"

// METHOD_*, TIR_*, DISPERSION_SEARCH_*: the parameters' choices (Shared.h).
// Incidence angles this close past the critical angle leave grazing instead of reflecting
// totally (TIR reflect): the normals read back from the layers are good to a few degrees, not
// enough to tell the two apart, and a grazing exit is the limit refraction tends to there (at
// ISR's estimated exits: kEstimatedTirBand, optics.glsl). Near an outline the filtered normal
// is good to 2-4 degrees (filteredNormal), and a segment that began there carries that error to
// its far end: crossings at or after such a normal have the wider band.
#ifndef CAPTURE_PAIR
#define CAPTURE_PAIR 0
#endif
#ifndef LAYER_METHOD
#define LAYER_METHOD METHOD_DIR
#endif
#ifndef HYBRID_LIST
#define HYBRID_LIST 0
#endif
const bool kPairCapture = CAPTURE_PAIR != 0, kTrace = LAYER_METHOD == METHOD_TRACE;
// The papers' model judges TIR at its limit, by its mip-filtered normals; the traced normals are
// the surface's own (no band).
const float kTirBand = kPairCapture ? 0.0 : radians(2.5), kOutlineTirBand = radians(4.0);
const int kMaxPasses = 3; // crossings without an interface a walk follows

// The method and the dispersion search are compiled in (a variant each, walkPrograms): on a CPU
// rasteriser a shader pays for the code it carries.
#ifndef LAYER_DISPERSION
#define LAYER_DISPERSION DISPERSION_NONE // else DISPERSION_SEARCH_*
#endif
const int kMethod = LAYER_METHOD;

uniform int uSteps, uMarchSteps, uInterfaces, uTirPolicy, uBounces, uDebug;
uniform mat4 uInverseProjection;
// trace-samples rays a pixel, one draw each (Mesa's llvmpipe ends a shader invocation's loops
// after 65535 iterations in all: a draw a sample keeps each within that): this draw's, and the
// weight of each.
uniform int uTraceSample;
uniform float uTraceWeight;
uniform int uHybridCriteria; // hybrid-criteria: what hands a pixel to the trace (main)
uniform int uTraceSamples;   // trace-samples

#if HYBRID_LIST // the hybrid's walk and its trace pass
// The hybrid's pixels handed to the trace (GpuState::handedOver): their count, the trace pass's
// work groups of 64 (walk_trace.comp.glsl's indirect dispatch), then a bit a pixel (row by
// row, handedOverListStart words) and the list of the pixels (x | y << 16).
layout(std430, binding = HANDED_OVER_BINDING) buffer HandedOver {
    uint handedOverCount, handedOverGroups[3];
    uint handedOverWords[];
};

uint handedOverListStart() {
    return (uint(uViewportSize.x) * uint(uViewportSize.y) + 31u) / 32u;
}

// Pixel p's bit of the hybrid's handed-over pixels.
uvec2 handedOverBit(ivec2 p) {
    uint i = uint(p.y) * uint(uViewportSize.x) + uint(p.x);
    return uvec2(i / 32u, 1u << (i % 32u));
}
#endif

// The view direction of trace sample uTraceSample through pixel p: the pixel's centre first,
// then jittered points of it (a fixed R2 sequence).
vec3 sampleView(ivec2 p, vec3 centre) {
    if (uTraceSample == 0)
        return centre;
    vec2 jitter = fract(0.5 + float(uTraceSample) * vec2(0.7548777, 0.5698403)) - 0.5;
    vec4 sub =
        uInverseProjection * vec4((vec2(p) + 0.5 + jitter) / uViewportSize * 2.0 - 1.0, 1.0, 1.0);
    return normalize(sub.xyz / sub.w);
}

float orderedToFloat(int i) {
    return intBitsToFloat(i < 0 ? i ^ 0x7FFFFFFF : i);
}

// The view-space box of every glass vertex this frame (rectangle.comp.glsl).
void glassBox(out vec3 lo, out vec3 hi) {
    lo = vec3(orderedToFloat(glassBoxMin[0]), orderedToFloat(glassBoxMin[1]),
              orderedToFloat(glassBoxMin[2]));
    hi = vec3(orderedToFloat(glassBoxMax[0]), orderedToFloat(glassBoxMax[1]),
              orderedToFloat(glassBoxMax[2]));
}

ivec2 pixelOf(vec3 X) {
    return ivec2(floor(projectToUv(X) * uViewportSize));
}

// Wyman's exit normal where the ray leaves the glass's outline: its direction in the plane square
// to the line of sight.
vec3 silhouetteNormal(vec3 dir) {
    return normalize(vec3(dir.xy, 0.0) + vec3(0.0, 0.0, 1e-6));
}

struct Crossing {
    bool found;
    bool silhouette; // the ray left every layer of the pixel (no surface recorded there)
    vec3 point;      // the last point before the interface
    vec3 beyond;     // the first point found past it
    uvec2 attr;      // the layer crossed
    int steps;
};

// Where P + t dir leaves the box [lo, hi] (t > 0), at most `limit`.
float boxExit(vec3 P, vec3 dir, vec3 lo, vec3 hi, float limit) {
    vec3 inv = 1.0 / (abs(dir) + 1e-20) * sign(dir + 1e-20);
    vec3 t0 = (lo - P) * inv, t1 = (hi - P) * inv;
    vec3 tFar = max(t0, t1);
    return min(min(tFar.x, tFar.y), min(tFar.z, limit));
}

// The layer of pixel p the ray passed on its way to depth z: the deepest one in front of z when
// it goes deeper, the nearest one behind z when it comes toward the camera (the layer whose
// passing changed the pixel's count). `nearest` (an estimated point, ISR), or no such layer:
// the layer nearest z.
bool pickLayer(ivec2 p, float z, bool deeper, bool nearest, out uvec2 attr) {
    attr = uvec2(0u);
    int passed = -1, closest = -1;
    float passedDepth = deeper ? -1.0 : 3.0e38, closestGap = 3.0e38;
    bool overflow = false;
    for (int g = 0; g < kDepthGroups; ++g) {
        vec4 stored = storedMap(p, g);
        overflow = overflow || (g == 0 && stored.x < 0.0);
        vec4 d = abs(stored);
        for (int k = 0; k < 4; ++k) {
            if (d[k] >= 1.0e38)
                continue;
            int i = 4 * g + k;
            if (deeper ? d[k] <= z && d[k] > passedDepth : d[k] >= z && d[k] < passedDepth) {
                passed = i;
                passedDepth = d[k];
            }
            if (abs(d[k] - z) < closestGap) {
                closestGap = abs(d[k] - z);
                closest = i;
            }
        }
    }
    if (closest < 0)
        return false;
    attr = layerAttrOf(p, passed >= 0 && !nearest ? passed : closest, overflow);
    return true;
}

// The normal at a crossing, filtered like a texture lookup (DIR reads its normal map with
// bilinear filtering): the four texels around the point, each by its layer of the same glass
// nearest the point's depth (within 2%), front or back (near an outline, where crossings graze,
// they meet), weighted bilinearly. Near an outline (the normal within about 30 degrees of
// square to the line of sight) texels without the surface lie past it, where its normal is
// square to the line of sight: they count with that normal, continuing the others' direction
// (`outline`: the normal was continued so, good to 2-4 degrees on a sphere).
vec3 filteredNormal(vec3 X, uvec2 attr, out bool outline) {
    vec2 texel = projectToUv(X) * uViewportSize - 0.5;
    ivec2 base = ivec2(floor(texel));
    vec2 f = texel - vec2(base);
    float z = -X.z;
    uint glass = layerGlass(attr);
    vec3 sum = vec3(0.0);
    float missing = 0.0;
    outline = false;
    for (int k = 0; k < 4; ++k) {
        ivec2 offset = ivec2(k & 1, k >> 1), q = base + offset;
        int best = -1;
        bool overflow = false;
        float gap = 0.02 * z;
        for (int g = 0; g < kDepthGroups; ++g) {
            vec4 stored = storedMap(q, g);
            overflow = overflow || (g == 0 && stored.x < 0.0);
            vec4 d = abs(stored);
            for (int j = 0; j < 4; ++j)
                if (abs(d[j] - z) < gap) {
                    gap = abs(d[j] - z);
                    best = 4 * g + j;
                }
        }
        vec2 w = mix(1.0 - f, f, vec2(offset));
        if (best < 0) {
            missing += w.x * w.y;
            continue;
        }
        uvec2 a = layerAttrOf(q, best, overflow);
        if (layerGlass(a) != glass) {
            missing += w.x * w.y;
            continue;
        }
        sum += w.x * w.y * layerNormal(a);
    }
    if (length(sum) <= 1e-6)
        return layerNormal(attr);
    vec3 n = normalize(sum);
    vec3 V = normalize(X);
    vec3 across = n - dot(n, V) * V;
    outline = missing > 0.0 && length(across) > 0.85;
    if (outline)
        n = normalize(sum + missing * normalize(across));
    return n;
}

// The next interface along P + t dir after a crossing, the ray in a segment of layer parity
// `parity`.
Crossing searchLayers(vec3 P, vec3 dir, int parity, bool inGlass) {
    Crossing c = Crossing(false, false, P, P, uvec2(0u), 0);
    vec3 lo, hi;
    glassBox(lo, hi);
    float margin = 1e-3 * length(hi - lo);
    float tEnd = boxExit(P, dir, lo - margin, hi + margin, 1.0e30);
    if (dir.z > 0.0) // toward the camera: stop at the near plane
        tEnd = min(tEnd, (-uNear * 1.001 - P.z) / dir.z);
    if (!(tEnd > 0.0))
        return c;
    ScreenRay r = screenRay(P, P + dir * tEnd);
    float pixels = length((r.uvE - r.uvS) * uViewportSize);
    // The segment starts just past the interface (the layer crossed is behind it).
    float pixel = 1.0 / max(pixels, 1e-3);
    float start = min(0.5 * pixel, 0.5), inside = start, outside = -1.0;
    // Coarse samples (one per four pixels in glass, per eight in air, where the glass to meet
    // next is a whole other piece; march-steps at most, half that in air) until the ray leaves the
    // segment, then (outside the loop: the SIMD lanes of a shader all run it together) the
    // conservative binary search between the last sample in the segment and the first out of
    // it: advance only to points still in it. A parity change that is gone again a pixel and a
    // half further is a graze of a silhouette, where a pixel's layers stand for a line of sight
    // the ray only passes beside: the search goes on behind it (twice at most).
    int steps = clamp(int(ceil(pixels / (inGlass ? 4.0 : 8.0))), 1,
                      max(inGlass ? uMarchSteps : uMarchSteps / 2, 1));
    for (int pass = 0; pass < 3; ++pass) {
        inside = start;
        outside = -1.0;
        for (int i = 1; i <= steps; ++i) {
            float a = start + (1.0 - start) * float(i) / float(steps);
            if (!marchHolds(r, inside, a, MARCH_LAYERS, parity)) {
                outside = a;
                break;
            }
            inside = a;
        }
        if (outside < 0.0)
            return c;
        c.steps += refine(r, MARCH_LAYERS, parity, inside, outside, uSteps, false);
        float past = outside + 1.5 * pixel;
        if (pass == 2 || past >= 1.0 || !marchHolds(r, past, past, MARCH_LAYERS, parity))
            break;
        start = past;
    }
    vec3 X0 = pointAt(r, inside), X1 = pointAt(r, outside);
    c.found = true;
    c.point = X0;
    c.beyond = X1;
    c.silhouette = !pickLayer(pixelOf(X1), -X1.z, dir.z < 0.0, false, c.attr);
    return c;
}

#if CAPTURE_PAIR
// the front's and the back's outward normals, with mips
layout(binding = PAIR_NORMALS_UNIT) uniform sampler2D uPairNormals[2];
uniform float uNormalLod;

// The papers' search (DIR §3.2-3.3): the one march between the depths zFrom and zTo, refined
// from end to end (no coarse samples: the pair holds one surface a pixel to meet).
Crossing searchPair(vec3 P, vec3 dir, bool inGlass, bool first) {
    Crossing c = Crossing(false, true, P, P, uvec2(0u), 0);
    if (!inGlass)
        return c; // past the pair: nothing more
    bool back = dir.z < 0.0;
    float zBackMin = uintBitsToFloat(glassBackRange[0]), zBackMax = uintBitsToFloat(glassBackRange[1]);
    float zFrontMin = uintBitsToFloat(glassFrontMin);
    float zFrom = back ? max(zBackMin, -P.z) : -P.z, zTo = back ? zBackMax : zFrontMin;
    // The first exit is searched for only going deeper, the way to the back; where it cannot be,
    // the ray leaves where it is, by the silhouette's normal (as where the search left the map).
    if (back ? zBackMax <= 0.0 || (first && dir.z > -1e-6)
             : first || zFrontMin <= 0.0 || zFrontMin >= 3.0e38) {
        c.found = first;
        return c;
    }
    ScreenRay r = screenRay(P + dir * ((-zFrom - P.z) / dir.z), P + dir * ((-zTo - P.z) / dir.z));
    int test = back ? MARCH_BACK : MARCH_FRONT;
    float inside = 0.0, outside = 1.0;
    c.steps = refine(r, test, 0, inside, outside, uSteps, true);
    ivec2 p = pixelAt(r, fractionAt(r, inside));
    c.silhouette = storedMap(p, 0)[back ? 1 : 0] >= 1.0e38;
    c.found = first || !c.silhouette;
    c.point = c.beyond = mix(r.S, r.E, inside);
    c.attr = layerAttrAt(p, back ? 1 : 0);
    return c;
}

// The normal where a crossing of the pair leaves the glass, read from the layer's mip-filtered
// map; where it faces the ray (the exit missed the far side), the silhouette's.
vec3 pairNormal(Crossing c, vec3 dir, out bool outline) {
    outline = false;
    vec3 n = textureLod(uPairNormals[layerFront(c.attr) ? 0 : 1], projectToUv(c.beyond), uNormalLod).xyz;
    return length(n) > 1e-4 && dot(n, dir) > 0.0 ? normalize(n) : silhouetteNormal(dir);
}
#endif

#if LAYER_METHOD == METHOD_TRACE
#include "refraction/trace.glsl"
#endif

// The next interface along P + t dir (the walk's exit finder, but ISR's first): traced, searched
// in the pair or searched in the layers; and its normal.
Crossing searchExit(vec3 P, vec3 dir, int parity, bool inGlass, bool first) {
#if LAYER_METHOD == METHOD_TRACE
    return traceCrossing(P, dir);
#elif CAPTURE_PAIR
    return searchPair(P, dir, inGlass, first);
#else
    return searchLayers(P, dir, parity, inGlass);
#endif
}

vec3 crossingNormal(Crossing c, vec3 dir, out bool outline) {
    outline = false;
#if LAYER_METHOD == METHOD_TRACE
    return layerNormal(c.attr);
#elif CAPTURE_PAIR
    return pairNormal(c, dir, outline);
#else
    return filteredNormal(c.beyond, c.attr, outline);
#endif
}

// ISR (Wyman 2005) on the layers: the exit estimated from the entry, d interpolated between
// d_V (to the next layer of the entry's pixel) and the entry layer's d_N by theta_t / theta_i.
Crossing estimateExit(vec3 P1, vec3 V, vec3 N1, vec3 T1, float eta, uvec2 entryAttr) {
    Crossing c = Crossing(true, false, P1, P1, uvec2(0u), 0);
    float z1 = -P1.z, next = 0.0;
    for (int g = 0; g < kDepthGroups; ++g) {
        vec4 d = layerDepths(pixelOf(P1), g);
        for (int k = 0; k < 4; ++k)
            if (d[k] < 1.0e38 && d[k] > z1 + 1e-5 * z1 && (next == 0.0 || d[k] < next))
                next = d[k];
    }
    float dV = next > 0.0 ? (next - z1) / max(abs(V.z), 1e-4) : 0.0;
    float d = wymanDistance(V, N1, T1, eta, dV, layerNormalDistance(entryAttr, z1));
    // Nothing to estimate from (an open surface: no layer behind the entry, no d_N): no exit,
    // as DIR's search finds none there; the ray leaves in its refracted direction.
    c.found = d > 1e-5 * z1;
    c.point = P1 + d * T1;
    c.beyond = c.point;
#if CAPTURE_PAIR
    // The back there, or Wyman's silhouette normal (crossingNormal).
    c.attr = layerAttrAt(pixelOf(c.point), 1);
    c.silhouette = layerDepths(pixelOf(c.point), 0).y >= 1.0e38;
#else
    // No layer there, or one facing the ray (the estimate fell short of the far side, or past
    // the outline): Wyman's silhouette normal.
    c.silhouette = !pickLayer(pixelOf(c.point), -c.point.z, T1.z < 0.0, true, c.attr) ||
                   dot(layerNormal(c.attr), T1) <= 0.0;
#endif
    return c;
}

// One path through the layers, for the indices of channel `channel`.
struct Walk {
    vec3 point, dir;    // where the ray leaves for the lookup, and its direction
    vec3 weight;        // transmittance: absorption, Fresnel and base colour of what it crossed
    vec3 reflected;     // the share reflected toward the ray at the later interfaces into
                        // glass (times the environment once the walk ends)
    vec3 reflectedDir;  // their directions, weighted by the light they reflect
    float reflectedRoughness;
    vec3 lastIncoming;  // the last refraction: incoming direction, normal against it, media
    vec3 lastNormal;
    uint lastFrom, lastTo; // glass ids + 1, 0: air
    vec3 firstExit;
    bool tir, fallback;
    // It followed a total internal reflection the layers may not represent (tir also counts
    // grazing exits; handedOverBy).
    bool hardReflection;
    bool outline;       // a crossing's normal was filtered near an outline
    bool overflowed;    // a crossing's pixel held more than K layers (its pair stood in)
    bool opaque;        // the walk ended on the opaque scene, which it sees as `seen`
    vec3 seen;
    int interfaces, steps;
    int sightLayers;    // the layers on its pixel's line of sight (the hybrid's judge)
};

// The hybrid's reasons to trace a pixel so far, each a bit of uHybridCriteria: the pixel, or
// one where the walk crossed a surface, held more than K layers (1); the walk left the layers
// where it found no surface and took Wyman's silhouette normal (2); it followed a total
// internal reflection the layers may not represent (4, hardReflection); it crossed a surface
// whose normal was filtered near an outline (8).
//
// Each reflection is searched with normals good to a few degrees, and the searches stop after
// tir-bounces. At one sample a pixel, one reflection inside a lone piece (two layers on the
// line of sight) that sends the ray on deeper stays with the walk, which follows it about as
// well as one traced ray does (two thirds of CesiumMan's reflecting pixels); the second of a
// chain, one with more glass on the line of sight, or one that turns the ray back toward the
// camera goes to the trace. With more samples every reflection does: the traced paths
// converge as samples add up, and the walk's keep their normals' error. So does every one
// over the papers' two surfaces. A grazing exit is never handed over: the trace does not
// improve it (on a sphere, where light never reflects totally, such pixels lost 0.04 dB to
// DIR when handed over).
uint handedOverBy(Walk w) {
    return uint(uHybridCriteria) &
           ((w.sightLayers > kLayerCapacity || w.overflowed ? uint(HYBRID_OVERFLOW) : 0u) |
            (w.fallback ? uint(HYBRID_LEFT_LAYERS) : 0u) |
            (w.hardReflection ? uint(HYBRID_REFLECTION) : 0u) |
            (w.outline ? uint(HYBRID_OUTLINE) : 0u));
}

// The hybrid's first sample hands pixels over, which the trace pass shades afresh: its walk
// stops at the first reason (a debug view's goes on, to show the whole walk).
bool stopsToHandOver(Walk w) {
    return kMethod == METHOD_HYBRID && uTraceSample == 0 && uDebug == DEBUG_NONE && handedOverBy(w) != 0u;
}

float mediumIor(uint medium, int channel) {
    return medium == 0u ? 1.0 : glassMaterials[medium - 1u].ior[channel];
}

// The media around the ray: x up to four glass ids + 1, a byte each, the newest in the low
// byte (0: air); y the solid of each, byte for byte (so that leaving one reads no material). A
// fifth nested glass is not entered (its crossings pass straight).
uint topMedium(uvec2 media) {
    return media.x & 255u;
}

uint solidOf(uint medium) {
    return uint(glassMaterials[medium - 1u].emissive.w);
}

// Crossing a surface of `medium` (glass id + 1) against its outward normal enters it; along it
// leaves the most recent entry of the same solid (character), if any.
uvec2 crossMedium(uvec2 media, uint medium, bool entering) {
    uint solid = solidOf(medium);
    if (entering)
        return (media.x >> 24) != 0u ? media : (media << 8) | uvec2(medium, solid);
    for (int k = 0; k < 4; ++k) {
        if (((media.x >> (8 * k)) & 255u) != 0u && ((media.y >> (8 * k)) & 255u) == solid) {
            uvec2 below = k == 0 ? uvec2(0u) : media & uvec2((1u << (8 * k)) - 1u);
            uvec2 above = k == 3 ? uvec2(0u) : (media >> (8 * k + 8)) << (8 * k);
            return below | above;
        }
    }
    return media;
}

// An opaque part along P + t dir before c, the next crossing: the trace's in its BVH (c itself),
// the others' on screen; where along the ray, and what the ray sees there.
bool opaqueBefore(Crossing c, vec3 P, vec3 dir, out float hitT, out vec3 seen) {
    seen = vec3(0.0);
#if LAYER_METHOD == METHOD_TRACE
    hitT = length(c.point - P);
    if (tracedOpaque(c))
        seen = opaqueSeen(c, dir);
    return tracedOpaque(c);
#else
    ivec2 hit;
    bool met = uNearby != 0 && marchScene(P, dir, length(c.point - P), 12, hitT, hit);
    if (met)
        seen = texelFetch(uSceneColor, hit, 0).rgb;
    return met;
#endif
}

// What a walk's ray sees: the opaque part it ended on (hitT 0), or what lies beyond its last
// interface (lookup).
vec3 walkSees(Walk w, float roughness, out float hitT) {
    hitT = 0.0;
    return w.opaque ? w.seen : lookup(w.point, w.dir, roughness, !kTrace, hitT);
}

// A reflection the trace follows once the path it left ends: where it starts, its direction,
// the medium's absorption, its weight, the media, the medium's index, the interfaces crossed.
struct Branch {
    vec3 P, dir, sigma, weight;
    uvec2 media;
    float ior;
    int interfaces;
};

Walk walkLayers(vec3 P1, vec3 V, vec3 N1, uvec2 entryAttr, int channel) {
    uvec2 media = crossMedium(uvec2(0u), layerGlass(entryAttr) + 1u, true);
    // The medium's index and absorption (kept with it: a crossing reads one material).
    GlassMaterial entered = glassMaterials[layerGlass(entryAttr)];
    float ior = entered.ior[channel];
    vec3 sigma = entered.sigma.rgb;
    vec3 dir;
    refractRay(V, N1, 1.0 / ior, dir); // air into glass never reflects totally
    // Nothing crossed yet but the entry (from air into the top medium), reflected or hit.
    Walk w = Walk(P1, dir, vec3(1.0), vec3(0.0), vec3(0.0), 0.0, V, N1, 0u, topMedium(media), P1,
                  false, false, false, false, false, false, vec3(0.0), 1, 0,
                  kMethod == METHOD_HYBRID ? storedCount(pixelOf(P1)) : 0);
    vec3 P = P1;
    int parity = 1;
    int bounces = 0;
    uvec2 segmentEntry = entryAttr;
    bool segmentFromEntry = true; // the segment began where the ray entered glass (ISR)
    // Crossings that change no medium (overlapping glass, a surface met again in the samples)
    // are not interfaces: they pass straight on, a few times at most.
    // On a CPU rasteriser every lane of a SIMD group runs the loop's whole body as long as one
    // lane walks on: the environment's reflection in the interfaces into glass is looked up
    // once after it, in their mean direction (exact for one such interface).
    int passes = 0;
    bool segmentFromOutline = false; // the segment began at a normal filtered near an outline
    // The trace follows the first reflection at a later interface into glass as a path of its
    // own once this one ends (the reference follows both branches there): where it left, in
    // what, and its weight; the walk's, and the trace's others, see the environment.
    bool split = false;
    Branch reflection;
    vec3 reflectionSeen = vec3(0.0);
    Walk primary;
    for (int path = 0;; ++path) {
        while (kMethod != METHOD_SIR && w.interfaces < uInterfaces && passes <= kMaxPasses) {
            if (stopsToHandOver(w))
                break;
            uint inside = topMedium(media);
            Crossing c = kMethod == METHOD_ISR && inside != 0u && segmentFromEntry
                ? estimateExit(P, w.lastIncoming, w.lastNormal, dir, 1.0 / ior, segmentEntry)
                : searchExit(P, dir, parity, inside != 0u, segmentFromEntry);
            w.steps += c.steps;
            if (!c.found)
                break;
            // An opaque part before the next interface (inside the glass, or between two pieces)
            // ends the walk: the ray sees it, as the lookup after the walk sees the nearby scene.
            float hitT;
            if (opaqueBefore(c, P, dir, hitT, w.seen)) {
                if (inside != 0u)
                    w.weight *= exp(-sigma * hitT);
                P += dir * hitT;
                w.opaque = true;
                break;
            }
            if (inside != 0u)
                w.weight *= exp(-sigma * length(c.point - P));
            P = c.point;
            if (w.interfaces == 1)
                w.firstExit = P;
            ++w.interfaces;
            // The count's parity flips at a crossing; an estimated exit (ISR) lies near, not on,
            // the far side: there the count is read afresh.
            bool estimated = kMethod == METHOD_ISR && inside != 0u && segmentFromEntry;
            int parityBefore = parity;
            parity = estimated ? (inSegment(pixelOf(c.beyond), -c.beyond.z, -c.beyond.z, 0) ? 0 : 1)
                               : parity ^ 1;
            // The surface crossed: a recorded layer, or (the ray left the glass's outline) the
            // glass the ray is in, with Wyman's silhouette normal.
            if (c.silhouette && inside == 0u)
                break; // in air and off every layer: nothing more to cross
            // Every crossing of the pair from its glass leaves it.
            bool leaves = c.silhouette || kPairCapture;
            uint glass = leaves ? inside : layerGlass(c.attr) + 1u;
            vec3 N = c.silhouette ? silhouetteNormal(dir) : layerNormal(c.attr);
            w.fallback = w.fallback || c.silhouette;
            w.overflowed =
                w.overflowed || (!kTrace && storedCount(pixelOf(c.beyond)) > kLayerCapacity);
            uvec2 before = media;
            // A traced crossing knows its side from the winding; a layer's from its normal.
            bool enters = kTrace ? layerFront(c.attr) : dot(dir, N) < 0.0;
            media = crossMedium(media, glass, !leaves && enters);
            uint to = topMedium(media);
            segmentFromEntry = inside == 0u && to != 0u;
            segmentEntry = c.attr;
            if (inside == to) { // inside a glass that overlaps the one crossed: no interface
                P = c.beyond;
                --w.interfaces;
                ++passes;
                continue;
            }
            GlassMaterial g = glassMaterials[max(to, 1u) - 1u]; // to == 0: air
            float n1 = ior, n2 = to == 0u ? 1.0 : g.ior[channel];
            bool outline = false;
            if (!c.silhouette) // a pixel's own normal is too coarse where rays graze a surface
                N = crossingNormal(c, dir, outline);
            w.outline = w.outline || outline;
            vec3 facing = dot(N, dir) < 0.0 ? N : -N;
            vec3 T;
            if (refractRay(dir, facing, n1 / n2, T)) {
                segmentFromOutline = outline;
                if (to != 0u) {
                    // Into glass: Fresnel splits the light; the reflected part sees the
                    // environment (the trace's first: its path), the transmitted part goes on in
                    // the glass's colour.
                    float F = fresnel(uFresnelMode, dot(-dir, facing), n1 / n2);
                    if (kTrace && path == 0 && !split) {
                        split = true;
                        reflection = Branch(c.point, reflect(dir, facing), sigma, w.weight * F,
                                            before, n1, w.interfaces);
                    } else {
                        w.reflected += w.weight * F;
                        w.reflectedDir += dot(w.weight, vec3(1.0)) * F * reflect(dir, facing);
                        w.reflectedRoughness = g.sigma.w;
                    }
                    w.weight *= (1.0 - F) * g.baseColor.rgb;
                }
            } else {
                w.tir = true;
                float incidence = acos(clamp(dot(-dir, facing), 0.0, 1.0));
                float band = kTrace      ? 0.0
                             : estimated ? kEstimatedTirBand
                             : outline || segmentFromOutline ? kOutlineTirBand : kTirBand;
                bool grazing = incidence < asin(n2 / n1) + band;
                // A traced path reflects as often as its interfaces allow (tir-bounces bounds the
                // image-space searches, whose error grows with every bounce).
                if (uTirPolicy == TIR_REFLECT && (kTrace || bounces < uBounces) && !grazing) {
                    ++bounces;
                    dir = reflect(dir, facing);
                    w.hardReflection = w.hardReflection || kPairCapture || uTraceSamples > 1 ||
                                       bounces > 1 || w.sightLayers > 2 || dir.z > 0.0;
                    media = before; // still in the same medium
                    parity = parityBefore;
                    segmentFromEntry = false;
                    continue;
                }
                T = tangentExit(dir, -facing); // the papers' clamp: leave tangent to the surface
            }
            // Across the interface: the refracted ray starts on its far side, in the new medium.
            w.lastIncoming = dir;
            w.lastNormal = facing;
            w.lastFrom = inside;
            w.lastTo = to;
            dir = T;
            ior = n2;
            sigma = to == 0u ? vec3(0.0) : g.sigma.rgb;
            P = c.beyond;
        }
        w.point = P;
        w.dir = dir;
        if (path == 1) { // the reflection's path ended: what it sees, then the first path's end
            float unused;
            reflectionSeen = walkSees(w, entered.sigma.w, unused) * w.weight;
            primary.reflected = w.reflected;
            primary.reflectedDir = w.reflectedDir;
            primary.reflectedRoughness = w.reflectedRoughness;
            primary.tir = primary.tir || w.tir;
            primary.hardReflection = primary.hardReflection || w.hardReflection;
            primary.steps = w.steps;
            w = primary;
            break;
        }
        if (!split)
            break;
        primary = w;
        P = reflection.P;
        dir = reflection.dir;
        media = reflection.media;
        ior = reflection.ior;
        sigma = reflection.sigma;
        w.weight = reflection.weight;
        w.interfaces = reflection.interfaces;
        w.opaque = false;
        passes = 0;
    }
    if (dot(w.reflectedDir, w.reflectedDir) > 0.0)
        w.reflected *= environmentRadiance(uViewToWorld * normalize(w.reflectedDir),
                                           w.reflectedRoughness);
    w.reflected += reflectionSeen;
    return w;
}

vec3 shadeLayers(vec3 P1, vec3 V, vec3 N1, uvec2 entryAttr, out Walk green) {
    GlassMaterial m = glassMaterials[layerGlass(entryAttr)];
    green = walkLayers(P1, V, N1, entryAttr, 1);
    if (stopsToHandOver(green))
        return vec3(0.0);
    float hitT;
    vec3 seen = walkSees(green, m.sigma.w, hitT);
    vec3 transmitted = seen * green.weight + green.reflected;
    bool dispersion = m.ior.r != m.ior.b;
#if LAYER_DISPERSION == DISPERSION_SEARCH_SHARED
    if (dispersion) {
        // One walk: red and blue leave from green's last interface, bent there by their own
        // indices with the deviation their entry gave them, and see what green's ray met.
        vec3 T1g;
        refractRay(V, N1, 1.0 / m.ior.g, T1g);
        for (int c = 0; c < 3; c += 2) {
            vec3 T1c;
            refractRay(V, N1, 1.0 / m.ior[c], T1c);
            float eta = mediumIor(green.lastFrom, c) / mediumIor(green.lastTo, c);
            vec3 Tc = green.interfaces < 2
                          ? T1c
                          : channelExit(green.lastIncoming, green.lastNormal, eta, T1c - T1g, green.dir);
            transmitted[c] = channelSees(green.point, Tc, hitT, m.sigma.w)[c] * green.weight[c] +
                             green.reflected[c];
        }
    }
#elif LAYER_DISPERSION == DISPERSION_SEARCH_PER_CHANNEL
    if (dispersion) {
        for (int c = 0; c < 3; c += 2) {
            Walk w = walkLayers(P1, V, N1, entryAttr, c);
            float unused;
            transmitted[c] = walkSees(w, m.sigma.w, unused)[c] * w.weight[c] + w.reflected[c];
            green.tir = green.tir || w.tir;
        }
    }
#endif
    return glassColor(m, P1, V, N1, transmitted);
}

// A glass pixel's entry: its nearest captured layer (the pair's: its nearest front) and its
// farthest, and where the primary ray through the pixel's centre meets the nearest; false where
// the pixel has no glass in front of the opaque scene.
struct Entry {
    float z, far;      // the nearest and the farthest layer's depth
    int farthest;      // the farthest's index
    uvec2 attr;        // the nearest's attributes
    vec3 P1, V;        // the entry point and the primary ray's direction (view space)
};

bool pixelEntry(ivec2 p, out Entry e) {
    // The nearest and farthest layers from the depth map, then the nearest's attributes alone.
    e.z = 3.0e38;
    e.far = 0.0;
    e.farthest = 0;
    int nearest = -1;
    for (int g = 0; g < kDepthGroups; ++g) {
        vec4 d = layerDepths(p, g);
        for (int k = 0; k < 4; ++k) {
            if (d[k] >= 1.0e38)
                continue;
            if (d[k] < e.z) {
                e.z = d[k];
                nearest = 4 * g + k;
            }
            if (d[k] > e.far) {
                e.far = d[k];
                e.farthest = 4 * g + k;
            }
        }
    }
#if CAPTURE_PAIR
    // The papers' model enters at the nearest front (a back face nearer than it is not entered).
    nearest = e.z < 3.0e38 && layerDepths(p, 0).x < 1.0e38 ? 0 : -1;
    e.z = layerDepths(p, 0).x;
#endif
    if (nearest < 0 || e.z >= sceneDepthAt(p))
        return false;
    e.attr = layerAttrAt(p, nearest);
    vec4 ray = uInverseProjection * vec4((vec2(p) + 0.5) / uViewportSize * 2.0 - 1.0, 1.0, 1.0);
    vec3 direction = ray.xyz / ray.w;
    e.P1 = direction * (e.z / -direction.z);
    e.V = normalize(e.P1);
    return true;
}

#if LAYER_METHOD == METHOD_TRACE
// The traced path of trace sample uTraceSample through pixel p (its entry e), weighted: the
// first from the capture's nearest layer at the pixel's centre (its normal map), traced from
// the camera instead where the pixel overflowed (the fallback's normal is coarse); the others
// from jittered points of the pixel (sampleView), their entry traced from the camera;
// what lies behind the glass at p where a ray meets none first. With the ray's counts.
vec3 tracedSample(ivec2 p, Entry e, out Walk walk) {
    vec3 V = sampleView(p, e.V), P1 = e.P1;
    uvec2 attr = e.attr;
    vec3 color;
    if ((uTraceSample > 0 || storedCount(p) > kLayerCapacity) && !traceEntry(V, p, P1, attr)) {
        walk.fallback = walk.tir = walk.hardReflection = walk.outline = walk.overflowed = false;
        color = texelFetch(uSceneColor, p, 0).rgb;
    } else {
        vec3 N = layerNormal(attr);
        color = shadeLayers(P1, V, dot(N, V) > 0.0 ? -N : N, attr, walk);
    }
    if (gTraceRays > 0) {
        atomicAdd(glassTraceRays, uint(gTraceRays));
        uint before = atomicAdd(glassTraceSteps[0], uint(gTraceSteps));
        if (before + uint(gTraceSteps) < before)
            atomicAdd(glassTraceSteps[1], 1u); // the carry: the high word
        atomicMax(glassTraceMaxSteps, uint(gTraceSteps));
    }
    return color * uTraceWeight;
}
#endif
