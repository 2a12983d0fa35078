// The one screen-space march, which the walk's searches (over the layers, and the papers' over
// the pair) and the lookup of the nearby opaque scene share: a ray segment in texture space and
// the conservative binary search along it (DIR §3.2-3.3).
//   A segment S..E (DIR Eqs. 3-4): texture coordinates are linear along it in screen space and
//   so is 1/z, so a sample at screen fraction a costs no matrix product.
//   marchHolds: whether the ray at a is still where it began, by the test the caller names (a
//   constant, folded once inlined): still in a segment of the layers' parity (inSegment), still
//   before the pair's back or behind its front (layers 1 and 0 of the pair capture), still in
//   front of the opaque scene.
//   refine: the binary search between the last sample where the test held and the first where
//   it did not, each halving advancing only to a point where it still holds (in screen
//   fraction, or along the ray in view space).
#ifndef REFRACTION_MARCH_GLSL
#define REFRACTION_MARCH_GLSL
#include "refraction/passes/layers.glsl"
#include "refraction/view.glsl"

layout(binding = SCENE_DEPTH_UNIT) uniform sampler2D uSceneDepth;
uniform float uNear, uFar;

const int MARCH_LAYERS = 0, MARCH_FRONT = 1, MARCH_BACK = 2, MARCH_SCENE = 3;


// The view depth of the opaque scene at pixel p (3e38 where it shows the environment, and off
// screen).
float sceneDepthAt(ivec2 p) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(uViewportSize))))
        return NO_DEPTH;
    float d = texelFetch(uSceneDepth, p, 0).r;
    return d < 1.0 ? viewDepthOf(d, uNear, uFar) : NO_DEPTH;
}

struct ScreenRay {
    vec3 S, E;        // view-space ends
    vec2 uvS, uvE;
    float invS, invE; // 1 / depth
};

ScreenRay screenRay(vec3 S, vec3 E) {
    return ScreenRay(S, E, projectToUv(S), projectToUv(E), -1.0 / S.z, -1.0 / E.z);
}

float depthAt(ScreenRay r, float a) {
    return 1.0 / mix(r.invS, r.invE, a);
}

ivec2 pixelAt(ScreenRay r, float a) {
    return ivec2(floor(mix(r.uvS, r.uvE, a) * uViewportSize));
}

// The view-space point at screen fraction a.
vec3 pointAt(ScreenRay r, float a) {
    float z = depthAt(r, a);
    float s = abs(r.E.z - r.S.z) > 1e-7 * abs(r.S.z) ? (-z - r.S.z) / (r.E.z - r.S.z) : a;
    return mix(r.S, r.E, clamp(s, 0.0, 1.0));
}

// The screen fraction of the point S + s (E - S).
float fractionAt(ScreenRay r, float s) {
    float inv = 1.0 / -mix(r.S.z, r.E.z, s);
    return abs(r.invE - r.invS) > 1e-12 * r.invS ? (inv - r.invS) / (r.invE - r.invS) : s;
}

// Whether the ray at fraction a (having come from fraction `from`) passes test `test`.
bool marchHolds(ScreenRay r, float from, float a, int test, int parity) {
    ivec2 p = pixelAt(r, a);
    float z = depthAt(r, a);
    if (test == MARCH_LAYERS)
        return inSegment(p, depthAt(r, from), z, parity);
    if (test == MARCH_SCENE)
        return z <= sceneDepthAt(p);
    float d = storedMap(p, 0)[test == MARCH_BACK ? 1 : 0];
    return d < UNUSED_DEPTH && (test == MARCH_BACK ? z < d : z > d);
}

#ifndef SCENE_DEPTH_TILES
#define SCENE_DEPTH_TILES 0
#endif
#if SCENE_DEPTH_TILES
// The opaque scene's nearest depth buffer value over tiles of 4 << L pixels at level L
// (scene_depth_tiles.comp.glsl), uSceneTileLevels levels.
layout(binding = SCENE_DEPTH_TILES_UNIT) uniform sampler2D uSceneDepthTiles;
uniform int uSceneTileLevels;

// Whether the segment r stays in front of the opaque scene wherever it is on screen: no tile
// under its pixels holds anything nearer than its far end, so that no sample along it can be
// behind the scene (a march along it meets nothing). False where it cannot tell: its pixels
// wider than the coarsest tiles.
bool segmentInFront(ScreenRay r) {
    // Its pixels, a hundredth of a pixel more each way for the rounding of a sample's place.
    vec2 last = uViewportSize - 1.0;
    vec2 lo = clamp(min(r.uvS, r.uvE) * uViewportSize - 0.01, vec2(0.0), last);
    vec2 hi = clamp(max(r.uvS, r.uvE) * uViewportSize + 0.01, vec2(0.0), last);
    // The finest level whose tiles are as wide as the pixels it spans: 2 x 2 tiles hold them.
    float extent = max(hi.x - lo.x, hi.y - lo.y) + 1.0;
    int level = 0;
    while (level + 1 < uSceneTileLevels && float(4 << level) < extent)
        ++level;
    if (float(4 << level) < extent)
        return false;
    ivec2 t0 = ivec2(lo) >> (level + 2), t1 = ivec2(hi) >> (level + 2);
    float nearest = min(min(texelFetch(uSceneDepthTiles, t0, level).r,
                            texelFetch(uSceneDepthTiles, ivec2(t1.x, t0.y), level).r),
                        min(texelFetch(uSceneDepthTiles, ivec2(t0.x, t1.y), level).r,
                            texelFetch(uSceneDepthTiles, t1, level).r));
    return nearest >= 1.0 || viewDepthOf(nearest, uNear, uFar) > 1.0001 * max(-r.S.z, -r.E.z);
}
#endif

// `halvings` halvings between inside (the test holds) and outside (it does not), the last
// accepted point `inside`; returns how many advanced. Halved in screen fraction, or `alongRay`
// in the parameter of S + s (E - S) (the papers' search, and the scene's: even steps in depth).
int refine(ScreenRay r, int test, int parity, inout float inside, inout float outside,
           int halvings, bool alongRay) {
    int advanced = 0;
    for (int k = 0; k < halvings; ++k) {
        float mid = 0.5 * (inside + outside);
        if (alongRay ? marchHolds(r, fractionAt(r, inside), fractionAt(r, mid), test, parity)
                     : marchHolds(r, inside, mid, test, parity)) {
            inside = mid;
            ++advanced;
        } else {
            outside = mid;
        }
    }
    return advanced;
}

#endif
