// Where a walk's next interface lies (part of walk.glsl, which includes it after its compiled-in
// choices and helpers): the Crossing the method finds from a point along a direction, and the
// normal there. DIR and the hybrid search the layers (searchLayers) or, over the pair capture,
// the papers' back and front depths (searchPair); ISR estimates its first exit (estimateExit);
// the trace meets the exact next hit in the glass BVH (trace.glsl). searchExit and
// crossingNormal choose among them.
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
// front, layer 1 the back, pair_resolve.frag.glsl) the walk is the papers' path: one piece of glass
// entered at the front and left at the back, its exit searched in the back depths (DIR §3.2-3.3)
// and, after a total internal reflection toward the camera, in the front ones, the normal there
// read mip-filtered (DIR §3.1); past the pair there is nothing more to cross.
#ifndef REFRACTION_WALK_CROSSINGS_GLSL
#define REFRACTION_WALK_CROSSINGS_GLSL

struct Crossing {
    bool found;
    bool silhouette; // the ray left every layer of the pixel (no surface recorded there)
    vec3 point;      // the last point before the interface
    vec3 beyond;     // the first point found past it
    uvec2 attr;      // the layer crossed
    GlassSurface surface; // its glass's surface there
    int steps;
};

// No crossing (yet) from P.
Crossing noCrossing(vec3 P, bool silhouette) {
    return Crossing(false, silhouette, P, P, uvec2(0u),
                    GlassSurface(vec3(1.0), 1.0, 0.0, 0.0), 0);
}

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
// the layer nearest z. With its glass's surface there.
bool pickLayer(ivec2 p, float z, bool deeper, bool nearest, out uvec2 attr,
               out GlassSurface surface) {
    attr = uvec2(0u);
    surface = GlassSurface(vec3(1.0), 1.0, 0.0, 0.0);
    int passed = -1, closest = -1;
    float passedDepth = deeper ? -1.0 : NO_DEPTH, closestGap = NO_DEPTH;
    PixelLayers l = pixelLayers(p);
    for (int i = 0; i < kDepthSlots; ++i) {
        float d = layerDepth(l, i);
        if (d >= UNUSED_DEPTH)
            continue;
        if (deeper ? d <= z && d > passedDepth : d >= z && d < passedDepth) {
            passed = i;
            passedDepth = d;
        }
        if (abs(d - z) < closestGap) {
            closestGap = abs(d - z);
            closest = i;
        }
    }
    if (closest < 0)
        return false;
    int picked = passed >= 0 && !nearest ? passed : closest;
    attr = layerAttrOf(p, picked, l.overflow);
    surface = layerSurfaceOf(p, picked, attr, l.overflow);
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
#ifdef SKIP_NORMALS // glass-bench --skip normals: the crossed layer's own normal
    outline = false;
    return layerNormal(attr);
#endif
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
        float gap = 0.02 * z;
        PixelLayers l = pixelLayers(q);
        for (int i = 0; i < kDepthSlots; ++i)
            if (abs(layerDepth(l, i) - z) < gap) {
                gap = abs(layerDepth(l, i) - z);
                best = i;
            }
        vec2 w = mix(1.0 - f, f, vec2(offset));
        if (best < 0) {
            missing += w.x * w.y;
            continue;
        }
        uvec2 a = layerAttrOf(q, best, l.overflow);
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
    Crossing c = noCrossing(P, false);
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
#ifdef SKIP_SEARCH // glass-bench --skip search: the next layer on the start's line of sight
    float z = -P.z, next = dir.z < 0.0 ? NO_DEPTH : 0.0;
    PixelLayers l = pixelLayers(pixelOf(P));
    for (int i = 0; i < kDepthSlots; ++i) {
        float d = layerDepth(l, i);
        bool ahead = dir.z < 0.0 ? d > z * 1.0001 && d < next : d < z * 0.9999 && d > next;
        if (d < UNUSED_DEPTH && ahead)
            next = d;
    }
    if (next <= 0.0 || next >= NO_DEPTH || abs(dir.z) < 1e-6)
        return c;
    float t = (-next - P.z) / dir.z;
    c.found = true;
    c.point = P + dir * (t * 0.999);
    c.beyond = P + dir * (t * 1.001);
    c.silhouette =
        !pickLayer(pixelOf(c.beyond), -c.beyond.z, dir.z < 0.0, false, c.attr, c.surface);
    return c;
#else
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
#endif
    vec3 X0 = pointAt(r, inside), X1 = pointAt(r, outside);
    c.found = true;
    c.point = X0;
    c.beyond = X1;
    c.silhouette = !pickLayer(pixelOf(X1), -X1.z, dir.z < 0.0, false, c.attr, c.surface);
    return c;
}

#if CAPTURE_PAIR && LAYER_METHOD != METHOD_TRACE // (the trace reads neither its maps nor ranges)
#include "refraction/passes/pair_ranges.glsl"
// the front's and the back's outward normals, with mips
layout(binding = PAIR_NORMALS_UNIT) uniform sampler2D uPairNormals[2];
uniform float uNormalLod;

// The papers' search (DIR §3.2-3.3): the one march between the depths zFrom and zTo, refined
// from end to end (no coarse samples: the pair holds one surface a pixel to meet).
Crossing searchPair(vec3 P, vec3 dir, bool inGlass, bool first) {
    Crossing c = noCrossing(P, true);
    if (!inGlass)
        return c; // past the pair: nothing more
    bool back = dir.z < 0.0;
    float zBackMin = uintBitsToFloat(pairBackRange[0]), zBackMax = uintBitsToFloat(pairBackRange[1]);
    float zFrontMin = uintBitsToFloat(pairFrontMin);
    float zFrom = back ? max(zBackMin, -P.z) : -P.z, zTo = back ? zBackMax : zFrontMin;
    // The first exit is searched for only going deeper, the way to the back; where it cannot be,
    // the ray leaves where it is, by the silhouette's normal (as where the search left the map).
    if (back ? zBackMax <= 0.0 || (first && dir.z > -1e-6)
             : first || zFrontMin <= 0.0 || zFrontMin >= NO_DEPTH) {
        c.found = first;
        return c;
    }
    ScreenRay r = screenRay(P + dir * ((-zFrom - P.z) / dir.z), P + dir * ((-zTo - P.z) / dir.z));
    int test = back ? MARCH_BACK : MARCH_FRONT;
    float inside = 0.0, outside = 1.0;
    c.steps = refine(r, test, 0, inside, outside, uSteps, true);
    ivec2 p = pixelAt(r, fractionAt(r, inside));
    c.silhouette = storedMap(p, 0)[back ? 1 : 0] >= UNUSED_DEPTH;
    c.found = first || !c.silhouette;
    c.point = c.beyond = mix(r.S, r.E, inside);
    c.attr = layerAttrAt(p, back ? 1 : 0);
    c.surface = layerSurfaceOf(p, back ? 1 : 0, c.attr, false);
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
    Crossing c = noCrossing(P1, false);
    c.found = true;
    float z1 = -P1.z, next = 0.0;
    PixelLayers l = pixelLayers(pixelOf(P1));
    for (int i = 0; i < kDepthSlots; ++i)
        if (layerDepth(l, i) < UNUSED_DEPTH && layerDepth(l, i) > z1 + 1e-5 * z1 &&
            (next == 0.0 || layerDepth(l, i) < next))
            next = layerDepth(l, i);
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
    c.surface = layerSurfaceOf(pixelOf(c.point), 1, c.attr, false);
    c.silhouette = layerDepths(pixelOf(c.point), 0).y >= UNUSED_DEPTH;
#else
    // No layer there, or one facing the ray (the estimate fell short of the far side, or past
    // the outline): Wyman's silhouette normal.
    c.silhouette =
        !pickLayer(pixelOf(c.point), -c.point.z, T1.z < 0.0, true, c.attr, c.surface) ||
        dot(layerNormal(c.attr), T1) <= 0.0;
#endif
    return c;
}

#endif
