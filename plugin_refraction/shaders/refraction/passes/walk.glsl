// The walk (walk.frag.glsl, the one shading pass over the glass pixels; the hybrid's trace pass,
// hybrid_trace.comp.glsl, and the fresh samples' pass, fresh_samples.comp.glsl), whichever
// capture filled the layers: a pixel's primary ray enters the nearest captured layer and walks
// the others (layers.glsl) in texture space, refracting at every interface it crosses (or
// reflecting under total internal reflection) with the media on both sides, up to N
// interfaces; then it sees the nearby opaque
// scene or the environment (scene_lookup.glsl). An opaque part met between two interfaces
// (inside the glass, or between two pieces) ends the walk there. ARCHITECTURE.md ("How a ray
// walks the layers") has the figure. Compiled in: the capture (CAPTURE_PAIR), K, the method
// (how the walk finds an exit: SIR none, ISR Wyman's estimate, DIR a search, the trace the
// exact hit in the glass BVH, the hybrid DIR's search, handing the pixels it cannot represent
// to the trace pass), the dispersion search and the punctual lights.
//
// Every crossing is the optical model's (optics.glsl, crossInterface, the reference's too;
// docs/methods.md, "The optical model"): the media on both sides (a stack of entered glasses,
// each character one solid), refraction or total internal reflection where the index changes
// (straight on where it does not: overlapping parts of one solid), the reflectance of an
// interface into glass and the tint of a solid entered. The walk differs from the trace only in
// how it finds a crossing and in two approximations of its own: reflections at later
// interfaces into glass are looked up once, in their mean direction, and reflections at the
// edge of total internal reflection, where its normals are a few degrees off, leave grazing.
// The trace follows each reflection as a path of its own (to SPLIT_DEPTH; the rest see the
// environment along them), and with more than one sample a pixel samples rough glass's
// microfacets.
//
// How the walk finds each crossing (DIR's search over the layers and over the pair, ISR's
// estimate, the trace's hit): walk_crossings.glsl.
// The depths as the resolve pass copied them into maps (layers.glsl), one texel fetch a
// search sample; SIR's walk (WALK_DEPTH_MAPS 0) reads only its pixel's, from the arrays, and
// its frame makes no maps.
#ifndef WALK_DEPTH_MAPS
#define WALK_DEPTH_MAPS 1
#endif
#if WALK_DEPTH_MAPS
#define LAYER_DEPTH_MAPS
#endif
#include "refraction/passes/glass_extent.glsl"
#include "refraction/passes/glass_surface.glsl"
#include "refraction/passes/layers.glsl"
#include "refraction/passes/walk_counters.glsl"

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

// The method and the dispersion search are compiled in (a variant each, selectVariants): on a CPU
// rasteriser a shader pays for the code it carries.
#ifndef LAYER_DISPERSION
#define LAYER_DISPERSION DISPERSION_NONE // else DISPERSION_SEARCH_*
#endif
const int kMethod = LAYER_METHOD;

uniform int uSteps, uMarchSteps, uInterfaces, uTirPolicy, uBounces, uDebug;
uniform mat4 uInverseProjection;
// trace-samples rays a pixel, one draw each (Mesa's llvmpipe ends a shader invocation's loops
// after 65535 iterations in all: a draw a sample keeps each within that): this draw's, and the
// weight of each. SEVERAL_SAMPLES: the frame takes samples past a pixel's first (the trace's and
// the hybrid's trace-samples, or their fresh samples); where it takes one, the later samples'
// code is out.
#ifndef SEVERAL_SAMPLES
#define SEVERAL_SAMPLES 1
#endif
#if SEVERAL_SAMPLES
uniform int uTraceSample;
uniform float uTraceWeight;
#else
const int uTraceSample = 0;
const float uTraceWeight = 1.0;
#endif
uniform int uHybridCriteria; // hybrid-criteria: what hands a pixel to the trace (main)
uniform int uTraceSamples;   // trace-samples
// The trace's paths are sampled: several samples a pixel, or one a frame of a frame that
// accumulates (uFrameSeed seeds each frame's).
uniform int uSampled;
uniform int uFrameSeed;
// The frame's jitter where it accumulates: pixel p's centre sees what the unjittered frame shows
// at p + 0.5 + uFrameJitter (TemporalHistory::jittered).
uniform vec2 uFrameJitter;
// Every sample's entry traced from the camera, as the trace's later samples are: a frame that
// accumulates (the capture's entry, a rasterised fragment, is off near outlines by the
// triangles' interpolation, a bias no number of frames averages away).
uniform int uTracedEntry;
// The trace with several samples a pixel (or over frames) samples rough glass's microfacets and
// converges to the reference (but for the reflections past the splits, which see the
// environment); with one it runs the deterministic model (the reference's deterministic
// evaluation).
bool sampledPaths() {
    return kTrace && uSampled != 0;
}

#if HYBRID_LIST // the hybrid's walk and its trace pass
// The hybrid's pixels handed to the trace (refraction.handed_over, a buffer the walk creates):
// their count, the trace pass's work groups of 64 (hybrid_trace.comp.glsl's indirect dispatch),
// then a bit a pixel (row by row, handedOverListStart words) and the list of the pixels
// (x | y << 16).
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

// Pixel p into the list of those that take the fresh samples (walk_counters.glsl).
void listFresh(ivec2 p) {
    uint slot = atomicAdd(walkFreshPixels, 1u);
    freshPixelList[slot] = uint(p.x) | uint(p.y) << 16;
    if (slot % 64u == 0u)
        atomicAdd(freshGroups[0], 1u);
}

// Where trace sample uTraceSample lies in pixel p, from the pixel's centre (the frame's
// jittered one where it accumulates) in pixels: the centre first, then points of the pixel (an
// R2 sequence), placed in the pixel itself rather than around its jittered centre. A frame that
// accumulates turns the sequence by its index in the history (a Cranley-Patterson rotation), so
// that a pixel sampled on frame after frame covers its area rather than the same points.
vec2 sampleOffset() {
    if (uTraceSample == 0)
        return vec2(0.0);
    vec2 turn = fract(float(uFrameSeed) * vec2(0.6180340, 0.4142136));
    return fract(0.5 + float(uTraceSample) * vec2(0.7548777, 0.5698403) + turn) - 0.5 -
           uFrameJitter;
}

// The view direction of trace sample uTraceSample through pixel p (`centre`: its centre's).
vec3 sampleView(ivec2 p, vec3 centre) {
    if (uTraceSample == 0)
        return centre;
    vec4 sub = uInverseProjection *
               vec4((vec2(p) + 0.5 + sampleOffset()) / uViewportSize * 2.0 - 1.0, 1.0, 1.0);
    return normalize(sub.xyz / sub.w);
}

ivec2 pixelOf(vec3 X) {
    return ivec2(floor(projectToUv(X) * uViewportSize));
}

// Wyman's exit normal where the ray leaves the glass's outline: its direction in the plane square
// to the line of sight.
vec3 silhouetteNormal(vec3 dir) {
    return normalize(vec3(dir.xy, 0.0) + vec3(0.0, 0.0, 1e-6));
}

#include "refraction/passes/walk_crossings.glsl"

// A pixel's walk in one channel (for its indices): its primary path as it ended, with what
// the walk found on the way.
struct Walk {
    Path path;          // the primary path: where it leaves for the lookup, its direction, weight
    bool opaque;        // it ended on the opaque scene, which it sees as `seen`
    vec3 seen;
    vec3 light;         // what the rest gathered, weighted: the trace's branches and the
                        // reflections looked up along their own direction
    vec3 reflected;     // the walk's: the share reflected toward the ray at the later
                        // interfaces into glass (times the environment once the walk ends)
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
    bool overflowed;    // a crossing's pixel held more than K layers (its pair stood in; the
                        // hybrid records it)
    int steps;
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
#ifdef SKIP_HANDOVER // glass-bench --skip handover: the walk shades every pixel
    return 0u;
#endif
    return uint(uHybridCriteria) &
           ((w.sightLayers > kLayerCapacity || w.overflowed ? uint(HYBRID_OVERFLOW) : 0u) |
            (w.fallback ? uint(HYBRID_LEFT_LAYERS) : 0u) |
            (w.hardReflection ? uint(HYBRID_REFLECTION) : 0u) |
            (w.outline ? uint(HYBRID_OUTLINE) : 0u));
}

// The hybrid's first sample hands pixels over, which the trace pass shades afresh: its walk
// stops at the first reason (a debug view's goes on, to show the whole walk).
bool stopsToHandOver(Walk w) {
    return kMethod == METHOD_HYBRID && uTraceSample == 0 && uDebug == DEBUG_NONE &&
           handedOverBy(w) != 0u;
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
#elif !NEARBY_SCENE || defined(SKIP_SCENE) // (--skip scene): no opaque part between interfaces
    hitT = 0.0;
    return false;
#else
    ivec2 hit;
    bool met = marchScene(P, dir, length(c.point - P), 12, hitT, hit);
    if (met)
        seen = texelFetch(uSceneColor, hit, 0).rgb;
    return met;
#endif
}

// The roughness a path's lookup blurs by: its roughest interface, where rough glass's
// microfacets are not sampled.
float lookupRoughness(Path path) {
    return sampledPaths() ? 0.0 : path.roughness;
}

// What a path sees where it ends: the opaque part it ended on (hitT 0), or what lies beyond its
// last interface (lookup).
vec3 pathSees(Path path, bool opaque, vec3 seen, out float hitT) {
    hitT = 0.0;
    return opaque ? seen : lookup(path.P, path.dir, lookupRoughness(path), !kTrace, hitT);
}

vec3 walkSees(Walk w, out float hitT) {
    return pathSees(w.path, w.opaque, w.seen, hitT);
}

// The state of the search along a path: the layer parity of the segment it is in, the layer
// it entered that segment by, whether the segment began where the ray entered glass (ISR
// estimates it) or at a normal filtered near an outline, the reflections followed.
struct Segment {
    int parity;
    uvec2 entry;
    bool fromEntry, fromOutline;
    int bounces;
};

// The facet a crossing refracts or reflects about: a sampled microfacet of rough glass where
// the trace samples its paths, else the (facing) normal.
vec3 crossingFacet(vec3 N, vec3 dir, GlassSurface s, inout uint rng) {
    if (!sampledPaths() || s.roughness <= SMOOTH_ROUGHNESS)
        return N;
    vec2 u = vec2(random01(rng), random01(rng));
    return sampleMicrofacet(N, s.roughness, -dir, u);
}

// Whether the facet m that crossingFacet gave for normal N is a sampled microfacet (its share of
// the light then weighs the path): never where the paths are not sampled, whose code is out.
bool sampledFacet(vec3 m, vec3 N) {
    return sampledPaths() && m != N;
}

// The entry's path in channel `channel`: into the glass at P1 (view direction V, normal N1
// facing it), refracted (about a sampled microfacet of rough glass, the trace sampling).
Path entryPath(vec3 P1, vec3 V, vec3 N1, uvec2 entryAttr, GlassSurface s, int channel,
               inout uint rng) {
    uint medium = layerGlass(entryAttr) + 1u;
    GlassMaterial entered = glassMaterials[medium - 1u];
    Path path = Path(P1, V, vec3(1.0), crossMedium(uvec2(0u), medium, true),
                     entered.ior[channel], entered.sigma, s.roughness, 1, 0, 0);
    vec3 m = crossingFacet(N1, V, s, rng);
    if (!refractRay(V, m, 1.0 / path.ior, path.dir)) // only about a facet tilted far
        path.dir = reflect(V, m);
    if (sampledFacet(m, N1))
        path.weight *= microfacetWeight(path.dir, m, N1, s.roughness, true);
    return path;
}

// A walk starting at the entry P1 (view direction V, normal N1 facing it) on `path`.
Walk startWalk(vec3 P1, vec3 V, vec3 N1, Path path) {
    Walk w;
    w.path = path;
    w.opaque = false;
    w.seen = w.light = w.reflected = w.reflectedDir = vec3(0.0);
    w.reflectedRoughness = 0.0;
    w.lastIncoming = V;
    w.lastNormal = N1;
    w.lastFrom = 0u;
    w.lastTo = topMedium(path.media);
    w.firstExit = P1;
    w.tir = w.fallback = w.hardReflection = w.outline = w.overflowed = false;
    w.steps = 0;
    w.sightLayers = kMethod == METHOD_HYBRID ? storedCount(pixelOf(P1)) : 0;
    return w;
}

// Where a path ends: on the opaque scene (seen as `seen`), else past its last interface.
struct PathEnd {
    bool opaque;
    vec3 seen;
};

// The surface a crossing c meets (the path in `inside`): a recorded layer's glass, or where the
// ray left the glass's outline, or over the pair capture, the glass it is in, which it leaves
// (at the surface its layer holds); its normal (`N`, filtered where the layers give it: `outline` near an outline).
SurfaceMet crossingSurface(Crossing c, Path path, uint inside, out vec3 N, out bool outline) {
    bool leaves = c.silhouette || kPairCapture; // every crossing of the pair leaves its glass
    uint glass = leaves ? inside : layerGlass(c.attr) + 1u;
    N = c.silhouette ? silhouetteNormal(path.dir) : layerNormal(c.attr);
    // A traced crossing knows its side from the winding; a layer's from its normal.
    bool enters = !leaves && (kTrace ? layerFront(c.attr) : dot(path.dir, N) < 0.0);
    outline = false;
    if (!c.silhouette) // a pixel's own normal is too coarse where rays graze a surface
        N = crossingNormal(c, path.dir, outline);
    // Past the outline no layer holds the surface there: the material's.
    return SurfaceMet(glass, c.silhouette ? materialSurface(glassMaterials[glass - 1u]) : c.surface,
                      enters);
}

// The reflection of an interface the path (`before` it, `after` it) crossed at facet m of a
// surface facing `facing` of roughness `roughness`, from where the path met it, carrying
// `reflected` of its light.
Path mirrorPath(Path before, Path after, vec3 m, vec3 facing, vec3 reflected, float roughness) {
    Path mirror = before;
    mirror.dir = reflect(before.dir, m);
    mirror.weight =
        reflected *
        (sampledFacet(m, facing) ? microfacetWeight(mirror.dir, m, facing, roughness, false) : 1.0);
    mirror.interfaces = after.interfaces;
    mirror.crossings = after.crossings;
    mirror.roughness = max(before.roughness, roughness);
    return mirror;
}

// One step of a path: the next interface found (searched, estimated or traced), the segment
// up to it absorbed, the surface crossed (crossInterface); false where the path ends (on an
// opaque part: `end`). An interface into glass leaves its reflection in `mirror` (reflects).
// The walk's record (w) follows the primary path.
bool walkStep(inout Walk w, inout Path path, inout Segment seg, inout PathEnd end, int channel,
              bool primary, inout uint rng, out Path mirror, out bool reflects) {
    reflects = false;
    uint inside = topMedium(path.media);
    bool estimated = kMethod == METHOD_ISR && inside != 0u && seg.fromEntry;
    Crossing c = estimated ? estimateExit(path.P, w.lastIncoming, w.lastNormal, path.dir,
                                          1.0 / path.ior, seg.entry)
                           : searchExit(path.P, path.dir, seg.parity, inside != 0u, seg.fromEntry);
    w.steps += c.steps;
    if (!c.found)
        return false;
    // An opaque part before the next interface (inside the glass, or between two pieces) ends
    // the path: it sees it, as the lookup after the walk sees the nearby scene.
    float hitT;
    if (opaqueBefore(c, path.P, path.dir, hitT, end.seen)) {
        path.weight *= exp(-path.sigma * hitT);
        path.P += path.dir * hitT;
        end.opaque = true;
        return false;
    }
    path.weight *= exp(-path.sigma * length(c.point - path.P));
    path.P = c.point;
    if (primary && path.interfaces == 1)
        w.firstExit = path.P;
    // The count's parity flips at a crossing; an estimated exit (ISR) lies near, not on, the far
    // side: there the count is read afresh.
    int parityBefore = seg.parity;
    seg.parity = estimated ? (inSegment(pixelOf(c.beyond), -c.beyond.z, -c.beyond.z, 0) ? 0 : 1)
                           : seg.parity ^ 1;
    if (c.silhouette && inside == 0u)
        return false; // in air and off every layer: nothing more to cross
    vec3 N;
    bool outline;
    SurfaceMet met = crossingSurface(c, path, inside, N, outline);
    w.fallback = w.fallback || c.silhouette;
    w.overflowed = w.overflowed ||
                   (kMethod == METHOD_HYBRID && storedCount(pixelOf(c.beyond)) > kLayerCapacity);
    w.outline = w.outline || outline;
    vec3 facing = dot(N, path.dir) < 0.0 ? N : -N;
    vec3 m = crossingFacet(facing, path.dir, met.surface, rng);
    float band = kTrace ? 0.0 : estimated ? kEstimatedTirBand
                                          : outline || seg.fromOutline ? kOutlineTirBand : kTirBand;
    // A traced path reflects as often as its interfaces allow (tir-bounces bounds the
    // image-space searches, whose error grows with every bounce).
    bool mayReflect = uTirPolicy == TIR_REFLECT && (kTrace || seg.bounces < uBounces);
    Path before = path;
    vec3 reflected;
    int crossed = crossInterface(path, met, m, channel, band, mayReflect, reflected);
    if (crossed == CROSSED_PASSED) { // overlapping glass of one index: straight on
        path.P = c.beyond;
        return true;
    }
    if (sampledFacet(m, facing)) // a sampled microfacet's share of the light, the way it went
        path.weight *= microfacetWeight(path.dir, m, facing, met.surface.roughness,
                                        crossed != CROSSED_REFLECTED);
    w.tir = w.tir || crossed == CROSSED_REFLECTED || crossed == CROSSED_GRAZING;
    if (crossed == CROSSED_REFLECTED) {
        ++seg.bounces;
        w.hardReflection = w.hardReflection || kPairCapture || uSampled != 0 ||
                           seg.bounces > 1 || w.sightLayers > 2 || path.dir.z > 0.0;
        seg.parity = parityBefore;
        seg.fromEntry = false;
        return true;
    }
    // Across the interface: the refracted ray starts on its far side, in the new medium.
    seg = Segment(seg.parity, c.attr, inside == 0u && topMedium(path.media) != 0u, outline,
                  seg.bounces);
    if (primary) {
        w.lastIncoming = before.dir;
        w.lastNormal = facing;
        w.lastFrom = inside;
        w.lastTo = topMedium(path.media);
    }
    path.P = c.beyond;
    reflects = reflected != vec3(0.0);
    mirror = mirrorPath(before, path, m, facing, reflected, met.surface.roughness);
    return true;
}

// What becomes of the reflection of an interface into glass (`mirror`, left by `path`): the
// trace follows it as a path of its own once this one ends (`pending`) while it may split,
// else it sees the environment along it; the walk's are looked up once, after the walk.
void keepReflection(inout Walk w, inout Path path, Path mirror, inout Path pending[SPLIT_DEPTH],
                    inout int waiting) {
#if LAYER_METHOD == METHOD_TRACE
    if (path.splits < SPLIT_DEPTH && waiting < SPLIT_DEPTH &&
        max(max(mirror.weight.r, mirror.weight.g), mirror.weight.b) >= SPLIT_WEIGHT) {
        mirror.splits = ++path.splits;
        pending[waiting++] = mirror;
    } else { // the rest sees the environment along it (the reference picks a branch)
        w.light += mirror.weight *
                   environmentRadiance(uViewToWorld * mirror.dir, lookupRoughness(mirror));
    }
#else
    w.reflected += mirror.weight;
    w.reflectedDir += dot(mirror.weight, vec3(1.0)) * mirror.dir;
    w.reflectedRoughness = mirror.roughness;
#endif
}

// The walk of a pixel's refracted paths in channel `channel`, from the entry P1 (view direction
// V, normal N1 facing it, layer entryAttr, its surface s): the primary path step by step up to
// N interfaces (walkStep), then the trace's branches (keepReflection), each to its end.
Walk walkLayers(vec3 P1, vec3 V, vec3 N1, uvec2 entryAttr, GlassSurface s, int channel,
                inout uint rng) {
    Walk w = startWalk(P1, V, N1, entryPath(P1, V, N1, entryAttr, s, channel, rng));
    Path path = w.path;
    Segment seg = Segment(1, entryAttr, true, false, 0);
    Path pending[SPLIT_DEPTH]; // the trace's branches waiting to be walked
    for (int i = 0; i < SPLIT_DEPTH; ++i)
        pending[i] = path;
    int waiting = 0;
    // On a CPU rasteriser every lane of a SIMD group runs the loop's whole body as long as one
    // lane walks on.
    for (int branch = 0;; ++branch) {
        PathEnd end = PathEnd(false, vec3(0.0));
        Path mirror;
        bool reflects;
        while (kMethod != METHOD_SIR && path.interfaces < uInterfaces &&
               path.crossings < 2 * uInterfaces && !(branch == 0 && stopsToHandOver(w)) &&
               walkStep(w, path, seg, end, channel, branch == 0, rng, mirror, reflects))
            if (reflects)
                keepReflection(w, path, mirror, pending, waiting);
        float unused;
        if (branch == 0) {
            w.path = path;
            w.opaque = end.opaque;
            w.seen = end.seen;
        } else {
            w.light += pathSees(path, end.opaque, end.seen, unused) * path.weight;
        }
        if (waiting == 0)
            break;
        path = pending[--waiting];
        seg = Segment(1, uvec2(0u), false, false, 0);
    }
    // The walk's reflections at later interfaces into glass, looked up once after its loop, in
    // their mean direction (exact for one such interface).
    if (dot(w.reflectedDir, w.reflectedDir) > 0.0)
        w.light += w.reflected * environmentRadiance(uViewToWorld * normalize(w.reflectedDir),
                                                     w.reflectedRoughness);
    return w;
}

// Where green's path ended past its last point (walkSees' hitT), for its motion
// (walk_motion.glsl).
float gEndT = -1.0;

// The colour of a glass pixel's entry (P1, view direction V, normal N1 facing it, layer
// entryAttr, its surface s): its walks (green's, and red's and blue's by the dispersion
// search), then the light at the entry (glassColor).
vec3 shadeLayers(vec3 P1, vec3 V, vec3 N1, uvec2 entryAttr, GlassSurface s, inout uint rng,
                 out Walk green) {
    GlassMaterial m = glassMaterials[layerGlass(entryAttr)];
    green = walkLayers(P1, V, N1, entryAttr, s, 1, rng);
    if (stopsToHandOver(green))
        return vec3(0.0);
    float hitT;
    vec3 seen = walkSees(green, hitT);
    gEndT = hitT;
    vec3 transmitted = seen * green.path.weight + green.light;
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
            vec3 Tc = green.path.interfaces < 2
                          ? T1c
                          : channelExit(green.lastIncoming, green.lastNormal, eta, T1c - T1g,
                                        green.path.dir);
            transmitted[c] =
                channelSees(green.path.P, Tc, hitT, lookupRoughness(green.path))[c] *
                    green.path.weight[c] +
                green.light[c];
        }
    }
#elif LAYER_DISPERSION == DISPERSION_SEARCH_PER_CHANNEL
    if (dispersion) {
        for (int c = 0; c < 3; c += 2) {
            Walk w = walkLayers(P1, V, N1, entryAttr, s, c, rng);
            float unused;
            transmitted[c] = walkSees(w, unused)[c] * w.path.weight[c] + w.light[c];
            green.tir = green.tir || w.tir;
        }
    }
#endif
    return glassColor(m, s, P1, V, N1, transmitted);
}

// A glass pixel's entry: its nearest captured layer (the pair's: its nearest front) and its
// farthest, and where the primary ray through the pixel's centre meets the nearest; false where
// the pixel has no glass in front of the opaque scene.
struct Entry {
    float z, far;      // the nearest and the farthest layer's depth
    int nearest, farthest; // their indices
    uvec2 attr;        // the nearest's attributes
    GlassSurface surface; // its glass's surface there
    vec3 P1, V;        // the entry point and the primary ray's direction (view space)
};

bool pixelEntry(ivec2 p, out Entry e) {
    // The nearest and farthest layers from the depth map, then the nearest's attributes alone.
    e.z = NO_DEPTH;
    e.far = 0.0;
    e.farthest = 0;
    int nearest = -1;
    e.nearest = 0;
    PixelLayers l = pixelLayers(p);
    for (int i = 0; i < kDepthSlots; ++i) {
        float d = layerDepth(l, i);
        if (d >= UNUSED_DEPTH)
            continue;
        if (d < e.z) {
            e.z = d;
            nearest = i;
        }
        if (d > e.far) {
            e.far = d;
            e.farthest = i;
        }
    }
#if CAPTURE_PAIR
    // The papers' model enters at the nearest front (a back face nearer than it is not entered).
    nearest = e.z < NO_DEPTH && layerDepth(l, 0) < UNUSED_DEPTH ? 0 : -1;
    e.z = layerDepth(l, 0);
#endif
    if (nearest < 0 || e.z >= sceneDepthAt(p))
        return false;
    e.nearest = nearest;
    e.attr = layerAttrOf(p, nearest, l.overflow);
    e.surface = layerSurfaceOf(p, nearest, e.attr, l.overflow);
    vec4 ray = uInverseProjection * vec4((vec2(p) + 0.5) / uViewportSize * 2.0 - 1.0, 1.0, 1.0);
    vec3 direction = ray.xyz / ray.w;
    e.P1 = direction * (e.z / -direction.z);
    e.V = normalize(e.P1);
    return true;
}

// The nearest layer's normal at entry e, turned toward the viewer.
vec3 facingNormal(Entry e) {
    vec3 n = layerNormal(e.attr);
    return dot(n, e.V) > 0.0 ? -n : n;
}

// The random numbers of pixel p's sample uTraceSample (the trace's sampled paths).
uint sampleSeed(ivec2 p) {
    return uint(p.x) * 73856093u ^ uint(p.y) * 19349663u ^ uint(uTraceSample + 1) * 83492791u ^
           uint(uFrameSeed) * 2654435761u;
}

#if LAYER_METHOD == METHOD_TRACE
// The traced path of trace sample uTraceSample through pixel p (its entry e), weighted: the
// first from the capture's nearest layer at the pixel's centre (its normal map), traced from
// the camera instead where the pixel overflowed (the fallback's normal is coarse) or the frame
// accumulates (uTracedEntry); the others
// from jittered points of the pixel (sampleView), their entry traced from the camera;
// what lies behind the glass at p where a ray meets none first. With the ray's counts.
vec3 tracedSample(ivec2 p, Entry e, out Walk walk) {
    vec3 V = sampleView(p, e.V), P1 = e.P1;
    uvec2 attr = e.attr;
    GlassSurface surface = e.surface;
    vec3 color;
    uint rng = sampleSeed(p);
    if ((uTraceSample > 0 || uTracedEntry != 0 || storedCount(p) > kLayerCapacity) &&
        !traceEntry(V, p, P1, attr, surface)) {
        walk.fallback = walk.tir = walk.hardReflection = walk.outline = walk.overflowed = false;
        color = texelFetch(uSceneColor, p, 0).rgb;
    } else {
        vec3 N = layerNormal(attr);
        color = shadeLayers(P1, V, dot(N, V) > 0.0 ? -N : N, attr, surface, rng, walk);
    }
    if (gTraceRays > 0) {
        atomicAdd(walkTraceRays, uint(gTraceRays));
        uint before = atomicAdd(walkTraceSteps[0], uint(gTraceSteps));
        if (before + uint(gTraceSteps) < before)
            atomicAdd(walkTraceSteps[1], 1u); // the carry: the high word
        atomicMax(walkTraceMaxSteps, uint(gTraceSteps));
    }
    return color * uTraceWeight;
}
#else
// Whether layer entries a and b lie on one surface: one glass, depths within 5%.
bool sameEntrySurface(Entry a, Entry b) {
    return layerGlass(a.attr) == layerGlass(b.attr) && abs(a.z - b.z) <= 0.05 * min(a.z, b.z);
}

// A later sample's entry (at `offset` from pixel p's centre, its ray V), from the layers around
// it rather than the pixel's alone: the pixel whose square holds the point gives the surface
// (none: the sample misses the glass, and `behind` is the scene there), and the four pixels
// around it on that surface its normal and point, interpolated (bilinear, the pixels on other
// surfaces left out). Curved glass bends each point of a pixel its own way: the pixel's own
// normal at every point of it would give each sample one path.
bool subPixelEntry(ivec2 p, vec2 offset, vec3 V, inout Entry e, out vec3 N1, out vec3 behind) {
    ivec2 last = ivec2(uViewportSize) - 1;
    vec2 g = vec2(p) + 0.5 + offset;
    ivec2 q = clamp(ivec2(floor(g)), ivec2(0), last);
    behind = vec3(0.0);
    if (q != p) {
        Entry eq;
        if (!pixelEntry(q, eq)) {
            behind = texelFetch(uSceneColor, q, 0).rgb;
            return false;
        }
        e = eq;
    }
    vec2 t = floor(g - 0.5), f = g - 0.5 - t;
    vec3 normal = vec3(0.0), point = vec3(0.0);
    float total = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 r = clamp(ivec2(t) + o, ivec2(0), last);
        Entry er = e;
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        if (w <= 0.0 || (r != q && (!pixelEntry(r, er) || !sameEntrySurface(e, er))))
            continue;
        normal += w * facingNormal(er);
        point += w * er.P1;
        total += w;
    }
    N1 = normalize(normal);
    point /= total;
    float facing = dot(V, N1);
    e.P1 = facing < -0.05 ? V * (dot(point, N1) / facing) : V * (point.z / V.z);
    return true;
}

// Sample uTraceSample of the walk through pixel p (its entry e, the nearest layer's normal N1
// turned to the viewer, its `stored` layers), weighted: the first from the pixel's centre, the
// hybrid's later ones along their jittered rays (sampleView) from their own entries
// (subPixelEntry). A pixel the hybrid hands over for its own layers is
// not walked at all (black).
vec3 layeredSample(ivec2 p, Entry e, vec3 N1, int stored, out Walk walk) {
    walk.overflowed = walk.fallback = walk.hardReflection = walk.outline = false;
    walk.sightLayers = stored;
    uint rng = sampleSeed(p);
    vec3 V = sampleView(p, e.V), behind;
    if (uTraceSample > 0 && !subPixelEntry(p, sampleOffset(), V, e, N1, behind))
        return behind * uTraceWeight;
    if (stopsToHandOver(walk))
        return vec3(0.0);
    return shadeLayers(e.P1, V, N1, e.attr, e.surface, rng, walk) * uTraceWeight;
}
#endif
