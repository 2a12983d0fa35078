// What a glass pixel shows, as the temporal resolve reprojects it (common/motion.glsl;
// docs/methods.md, "Temporal accumulation"): the walk's and the hybrid trace pass's record of
// each glass pixel into the plugin's copy of the frame's motion. A pixel goes by what its light
// comes from:
//   - mostly reflected (the entry's reflectance over a half), or its path still in glass when
//     the walk ended: by the glass surface it enters (the capture's motion of that layer);
//   - else by the end of its refracted path, seen from the camera as a virtual point on the
//     primary ray at the path's length (primary surface replacement):
//       the environment: infinitely far, the camera's turn alone;
//       an opaque surface or the ground: the virtual point held still in the world, plus the
//       end's own motion where the opaque scene shows it (its motion there less the camera's),
//       none where it is hidden.
// Its identity is the glass it entered (what the path ends on may change from frame to frame,
// motionSubject), and the direction the path left the glass goes with it: the resolve rejects
// the history where another glass is entered, or where the exit turned by more than a right
// angle. A path's texel also carries the motion of the glass it entered, where the resolve looks
// first (a body moving over a still background carries its refraction with it).
#ifndef REFRACTION_WALK_MOTION_GLSL
#define REFRACTION_WALK_MOTION_GLSL
#include "common/motion.glsl"

layout(binding = MOTION_UNIT) uniform usampler2D uSceneMotion; // the opaque scene's

vec3 viewToWorld(vec3 X) {
    return uViewToWorld * X + uViewOriginWorld;
}

#ifdef GLASS_MOTION_READ
// The hybrid's trace pass (a compute shader, one storage block short of the walk's): the walk
// left each pixel it handed over the motion of the glass it enters, in its texel's z.
layout(rgba32ui, binding = MOTION_IMAGE_UNIT) uniform uimage2D uGlassMotion;

vec2 enteredSurfaceMotion(ivec2 p, Entry e) {
    return !writesMotion() ? vec2(0.0) : unpackHalf2x16(imageLoad(uGlassMotion, p).z);
}
#else
layout(rgba32ui, binding = MOTION_IMAGE_UNIT) uniform writeonly uimage2D uGlassMotion;

// The motion of the glass surface pixel p enters (entry e): its capture layer's; an
// overflowing pixel's fallback keeps none, its entry point is taken as still.
vec2 enteredSurfaceMotion(ivec2 p, Entry e) {
    if (!writesMotion())
        return vec2(0.0);
    if (layerOverflow(p)) {
        vec3 X = viewToWorld(e.P1);
        return pointMotion(X, X);
    }
    return unpackHalf2x16(layerMotion[pixelIndex(p) * uint(kLayerCapacity) + uint(e.nearest)]);
}
#endif

// What a pixel the hybrid's walk hands over leaves its trace pass: the motion of the glass it
// enters (glassPixelMotion's there).
uvec4 handedOverMotion(ivec2 p, Entry e) {
    uvec4 m = packMotion(motionIdentity(MOTION_GLASS, layerGlass(e.attr)), vec2(0.0), 0.0, 0.0, 0u);
    m.z = packHalf2x16(enteredSurfaceMotion(p, e));
    return m;
}

uvec4 throughGlassMotion(uint glass, vec2 motion, vec2 surface, uint exitDirection) {
    uvec4 m = packMotion(motionIdentity(MOTION_THROUGH_GLASS, glass), motion, 0.0, 0.0,
                         exitDirection);
    m.z = packHalf2x16(clamp(surface, vec2(-8192.0), vec2(8192.0)));
    return m;
}

// The motion texel of glass pixel p: entered at e, its green path `green` ending `endT` past
// its last point (0: on it, or at infinity where it met nothing: see walkSees).
uvec4 glassPixelMotion(ivec2 p, Entry e, Walk green, float endT) {
    uint glass = layerGlass(e.attr);
    GlassMaterial m = glassMaterials[glass];
    vec3 N1 = facingNormal(e);
    float reflected = fresnel(uFresnelMode, dot(-e.V, N1), 1.0 / m.ior.g);
    bool inGlass = !green.opaque && endT <= 0.0 && topMedium(green.path.media) != 0u;
    if (reflected > 0.5 || inGlass)
        return packMotion(motionIdentity(MOTION_GLASS, glass), enteredSurfaceMotion(p, e), 0.0,
                          0.0, 0u);
    uint exitDirection = motionDirection(uViewToWorld * green.path.dir);
    vec2 surface = enteredSurfaceMotion(p, e);
    vec3 Vw = uViewToWorld * e.V;
    if (!green.opaque && endT <= 0.0) // the environment
        return throughGlassMotion(glass, directionMotion(Vw), surface, exitDirection);
    vec3 E = green.path.P + green.path.dir * endT;
    vec3 virtualPoint = viewToWorld(e.V * (length(e.P1) + length(E - e.P1)));
    vec2 motion = pointMotion(virtualPoint, virtualPoint);
    ivec2 h = ivec2(floor(projectToUv(E) * uViewportSize));
    float seen = sceneDepthAt(h);
    if (seen < NO_DEPTH && abs(seen + E.z) < 0.02 * -E.z) { // else hidden: taken as still
        vec3 Ew = viewToWorld(E);
        motion += motionPixels(texelFetch(uSceneMotion, h, 0)) - pointMotion(Ew, Ew);
    }
    return throughGlassMotion(glass, motion, surface, exitDirection);
}

// While a frame accumulates and anything moves (uFreshSamples > 1), the glass pixels whose
// history the resolve will reject take uFreshSamples samples, every other pixel one: the first
// sample (the walk's, or the hybrid trace pass's for the pixels it takes) decides from the
// previous frame's motion and lists the pixel for the fresh samples' pass, which takes the
// others (fresh_samples.comp.glsl).
uniform int uFreshSamples;
// A pixel that takes them: its colour's alpha, minus the samples it will average (the resolve,
// render/temporal.frag.glsl, weighs it so; no other pass of the scene writes a negative alpha).
float freshAlpha() {
    return -float(uFreshSamples);
}
uniform float uFreshContrast;
layout(binding = HISTORY_UNIT) uniform sampler2D uHistoryColor;
layout(binding = HISTORY_UNIT + 1) uniform usampler2D uHistoryMotion;

// Whether the history shows what pixel p (its motion texel m) shows now, where m says it was:
// the resolve's test (temporal.frag.glsl) with the footprint taken on the history's side, a
// texel of the 3x3 around, as this frame's neighbours are still being drawn.
bool historyFound(ivec2 p, uvec4 m) {
    vec2 candidates[2];
    int count = motionCandidates(m, vec2(p) + 0.5, candidates);
    for (int i = 0; i < count; ++i) {
        ivec2 hp = ivec2(floor(vec2(p) + 0.5 - candidates[i]));
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                ivec2 q = hp + ivec2(x, y);
                if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(uMotionSize))) &&
                    showsSame(m, texelFetch(uHistoryMotion, q, 0)))
                    return true;
            }
    }
    return false;
}

// Whether the history, where pixel p's texel m first says it was, differs from the pixel's first
// sample `color` by more than uFreshContrast of the brighter (luminance).
bool historyDiffers(ivec2 p, uvec4 m, vec3 color) {
    vec2 candidates[2];
    motionCandidates(m, vec2(p) + 0.5, candidates);
    vec3 history =
        textureLod(uHistoryColor, (vec2(p) + 0.5 - candidates[0]) / uMotionSize, 0.0).rgb;
    const vec3 kLuma = vec3(0.25, 0.5, 0.25);
    float now = dot(color, kLuma), then = dot(history, kLuma);
    return abs(now - then) > uFreshContrast * max(max(now, then), 0.02);
}

// FRESH_SAMPLES 0: a variant for frames that take none (uFreshSamples 0: SIR, ISR and DIR
// always, the tracing methods on a still frame or with fresh-samples 1), whose test is out (a
// CPU rasteriser would run its history reads at every glass pixel all the same).
#ifndef FRESH_SAMPLES
#define FRESH_SAMPLES 1
#endif

// Whether pixel p (its motion texel m, its first sample's colour `color`) takes the fresh
// samples: its history will be rejected, or differs from it by uFreshContrast. Listed so for
// the later ones. Its first sample then weighs 1 / uFreshSamples, and its colour's alpha is
// freshAlpha(): the outline pass leaves it (its samples anti-alias its outlines).
bool takesFreshSamples(ivec2 p, uvec4 m, vec3 color) {
#if FRESH_SAMPLES
    bool fresh = !historyFound(p, m) || (uFreshContrast > 0.0 && historyDiffers(p, m, color));
    if (fresh)
        listFresh(p);
    return fresh;
#else
    return false;
#endif
}

#endif
