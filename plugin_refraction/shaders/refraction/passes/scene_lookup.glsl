// What a ray leaving the glass sees (the walk, walk.glsl): the opaque scene where the ray
// meets it on screen (the one march, march.glsl), else the ground where it meets its square,
// else the environment.
#ifndef REFRACTION_SCENE_LOOKUP_GLSL
#define REFRACTION_SCENE_LOOKUP_GLSL
#include "common/environment.glsl"
#include "common/ground.glsl"
#include "refraction/passes/march.glsl"

// Compiled in (the walk's variants): NEARBY_SCENE, the lookup meets the nearby opaque scene (the
// nearby option on, and opaque geometry in the frame); NEARBY_GROUND, it meets the ground square
// too (render::GroundPlane, drawn). Without them the environment alone: a CPU rasteriser runs
// a march or the ground's shading it carries, met or not.
#ifndef NEARBY_SCENE
#define NEARBY_SCENE 1
#endif
#ifndef NEARBY_GROUND
#define NEARBY_GROUND NEARBY_SCENE
#endif
uniform vec4 uGroundPlane; // the ground's height, centre x and z, half size
layout(binding = SCENE_COLOR_UNIT) uniform sampler2D uSceneColor;
uniform float uNearbyDistance;
uniform mat3 uViewToWorld; // rotation part of the inverse view matrix
uniform vec3 uViewOriginWorld; // the camera in world space

// Whether a ray that went from view depth `last` at pixel `lastPixel`, in front of the depth
// map, to depth `reached` at pixel `hitPixel`, behind it, crossed the surface seen there: its
// last point in front was in front of that surface too, within the step and the change of the
// depth map between the two pixels (a surface seen at a grazing angle). A ray that came from
// the side behind a small opaque part, from pixels of the environment, was behind it already.
bool crossesScene(float last, ivec2 lastPixel, float reached, ivec2 hitPixel) {
    float surface = sceneDepthAt(hitPixel), front = sceneDepthAt(lastPixel);
    float slack = abs(reached - last) + 0.01 * reached +
                  (front < UNUSED_DEPTH ? abs(front - surface) : 0.0);
    return last <= surface + slack;
}

// Where the ray P + t dir, 0 < t <= distance, meets the opaque scene on screen: true with t
// (hitT) and the texel there. Samples at distances growing with the square of their index (fine
// near P, where an opaque part inside glass is met), up to the near plane and the screen's
// edge. A surface is met where the ray goes from in front of the depth map to behind it, not
// where a ray that starts behind a surface (leaving glass behind a small opaque part) stays
// behind it, nor where it passes behind one from the side (crossesScene). The crossing is
// refined between the last sample in front and the first behind, so the lookup does not band
// with the step size, and judged there: met if the refined point lies within a thickness behind
// the surface and the ray crossed it (judged at the sample, rays falling to a far ground at a
// grazing angle, one step deep behind it, were refused and saw the sky).
bool marchScene(vec3 P, vec3 dir, float distance, int steps, out float hitT, out ivec2 hit) {
    hitT = -1.0;
    hit = ivec2(0);
    if (dir.z > 0.0)
        distance = min(distance, (-uNear - P.z) / dir.z);
    if (!(distance > 0.0))
        return false;
    ScreenRay r = screenRay(P, P + dir * distance);
#if SCENE_DEPTH_TILES && !defined(SKIP_SCENE_TILES) // glass-bench --skip scene_tiles
    if (segmentInFront(r))
        return false;
#endif
    bool inFront = marchHolds(r, 0.0, 0.0, MARCH_SCENE, 0);
    float previous = 0.0; // along the ray: S + s (E - S)
    for (int i = 1; i <= steps; ++i) {
        float s = float(i * i) / float(steps * steps), a = fractionAt(r, s);
        vec2 uv = mix(r.uvS, r.uvE, a);
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0))))
            break;
        bool front = marchHolds(r, a, a, MARCH_SCENE, 0);
        if (inFront && !front) {
            float lo = previous, hi = s;
            refine(r, MARCH_SCENE, 0, lo, hi, 6, true);
            vec3 H = mix(r.S, r.E, hi);
            ivec2 hp = pixelAt(r, fractionAt(r, hi));
            if (-H.z - sceneDepthAt(hp) < 0.125 * uNearbyDistance &&
                crossesScene(-mix(r.S.z, r.E.z, lo), pixelAt(r, fractionAt(r, lo)), -H.z, hp)) {
                hitT = hi * distance;
                hit = hp;
                return true;
            }
        }
        previous = s;
        inFront = front;
    }
    return false;
}

// Where the ray P + t dir (view space), t > 0, meets the ground square: t, or -1. Exact, at any
// distance and off screen (a ray through a pane sees the ground's far edge where it is).
float groundHit(vec3 P, vec3 dir) {
#if !NEARBY_GROUND
    return -1.0;
#endif
    vec3 o = uViewToWorld * P + uViewOriginWorld, d = uViewToWorld * dir;
    if (abs(d.y) < 1e-9)
        return -1.0;
    float t = (uGroundPlane.x - o.y) / d.y;
    vec2 q = abs(o.xz + t * d.xz - uGroundPlane.yz);
    return t > 0.0 && max(q.x, q.y) <= uGroundPlane.w ? t : -1.0;
}

// The ground shaded where the ray P + t dir meets it, seen along the ray.
vec3 groundSeen(vec3 P, vec3 dir, float t) {
    vec3 d = uViewToWorld * dir;
    return groundColor(uViewToWorld * P + uViewOriginWorld + t * d, -d, uGroundPlane.w / 8.0);
}

// What a ray leaving the glass sees, when the nearby scene is on: the opaque scene within the
// nearby distance (with `march`: the trace met none in its BVH), else the ground; else (or with
// it off) the environment, which `roughness` blurs. hitT: where along the ray, -1 for the
// environment.
vec3 lookup(vec3 P, vec3 dir, float roughness, bool march, out float hitT) {
    ivec2 hit;
#if NEARBY_SCENE && !defined(SKIP_SCENE) // glass-bench --skip scene: the ground and environment
    if (march && marchScene(P, dir, uNearbyDistance, 24, hitT, hit))
        return texelFetch(uSceneColor, hit, 0).rgb;
#endif
    hitT = groundHit(P, dir);
#if NEARBY_GROUND
    if (hitT > 0.0)
        return groundSeen(P, dir, hitT);
#endif
    return environmentRadiance(uViewToWorld * dir, roughness);
}

#endif
