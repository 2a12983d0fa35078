// What a ray leaving the glass sees, shared by both shading paths (glass_shading.glsl, the
// layered walk in layers_shade.frag.glsl): the opaque scene where the ray meets it on screen,
// else the environment.
#ifndef REFRACTION_SCENE_LOOKUP_GLSL
#define REFRACTION_SCENE_LOOKUP_GLSL
#include "common/environment.glsl"
#include "refraction/view.glsl"

uniform int uNearby;
uniform sampler2D uSceneColor, uSceneDepth;
uniform float uNear, uFar, uNearbyDistance;
uniform mat3 uViewToWorld; // rotation part of the inverse view matrix
uniform vec3 uViewOriginWorld; // the camera in world space

float linearDepth(float d) {
    float z = d * 2.0 - 1.0;
    return 2.0 * uNear * uFar / (uFar + uNear - z * (uFar - uNear));
}

// The texel of the depth and colour maps a clip-space point falls in (clamped to the map).
ivec2 clipTexel(vec4 C) {
    return ivec2(clamp(C.xy / C.w * 0.5 + 0.5, vec2(0.0), vec2(0.9999)) * uViewportSize);
}

// The view depth of the opaque scene at pixel p (3e38 where it shows the environment, and off
// screen).
float sceneDepthAt(ivec2 p) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(uViewportSize))))
        return 3.0e38;
    float d = texelFetch(uSceneDepth, p, 0).r;
    return d < 1.0 ? linearDepth(d) : 3.0e38;
}

// Whether a ray that went from view depth `last` at pixel `lastPixel`, in front of the depth
// map, to depth `reached` at pixel `hitPixel`, behind it, crossed the surface seen there: its
// last point in front was in front of that surface too, within the step and the change of the
// depth map between the two pixels (a surface seen at a grazing angle). A ray that came from
// the side behind a small opaque part, from pixels of the environment, was behind it already.
bool crossesScene(float last, ivec2 lastPixel, float reached, ivec2 hitPixel) {
    float surface = sceneDepthAt(hitPixel), front = sceneDepthAt(lastPixel);
    float slack = abs(reached - last) + 0.01 * reached +
                  (front < 1.0e38 ? abs(front - surface) : 0.0);
    return last <= surface + slack;
}

// Where the ray P + t dir, 0 < t <= distance, meets the opaque scene on screen: true with t
// (hitT) and the texel there. March in clip space: the point P + t dir projects to C0 + t Cd
// (linear in t), so each step costs a few multiply-adds, not a matrix product; depths compare
// in window space (no division per step but the perspective one). The steps grow with the
// square of their index (fine near P, where an opaque part inside glass is met).
bool marchScene(vec3 P, vec3 dir, float distance, int steps, out float hitT, out ivec2 hit) {
    hitT = -1.0;
    hit = ivec2(0);
    vec4 C0 = uProjection * vec4(P, 1.0);
    vec4 Cd = uProjection * vec4(dir, 0.0);
    float previous = 0.0;
    // A surface is met where the ray goes from in front of the depth map to behind it, not
    // where a ray that starts behind a surface (leaving glass behind a small opaque part) stays
    // behind it, nor where it passes behind one from the side (crossesScene).
    bool inFront = C0.z / C0.w * 0.5 + 0.5 <= texelFetch(uSceneDepth, clipTexel(C0), 0).r;
    for (int i = 1; i <= steps; ++i) {
        float t = distance * float(i * i) / float(steps * steps);
        vec4 C = C0 + t * Cd;
        if (C.w < uNear)
            break;
        vec3 ndc = C.xyz / C.w;
        if (any(greaterThanEqual(abs(ndc.xy), vec2(1.0))))
            break;
        vec2 uv = ndc.xy * 0.5 + 0.5;
        float d = texelFetch(uSceneDepth, ivec2(uv * uViewportSize), 0).r;
        bool behind = d < 1.0 && ndc.z * 0.5 + 0.5 > d;
        if (behind && inFront) {
            // Refine the crossing between the last step in front and this one (binary search),
            // so the lookup does not band with the step size, and judge it there: met if the
            // refined point lies within a thickness behind the surface and the ray crossed it.
            // Judged at the step, rays falling to a far ground at a grazing angle, one step deep
            // behind it, were refused and saw the sky.
            float lo = previous, hi = t;
            for (int k = 0; k < 6; ++k) {
                float mid = 0.5 * (lo + hi);
                vec4 M = C0 + mid * Cd;
                float md = texelFetch(uSceneDepth, clipTexel(M), 0).r;
                if (md < 1.0 && M.z / M.w * 0.5 + 0.5 > md)
                    hi = mid;
                else
                    lo = mid;
            }
            vec4 H = C0 + hi * Cd, L = C0 + lo * Cd;
            if (H.w - sceneDepthAt(clipTexel(H)) < 0.125 * uNearbyDistance &&
                crossesScene(L.w, clipTexel(L), H.w, clipTexel(H))) {
                hitT = hi;
                hit = clipTexel(H);
                return true;
            }
        }
        previous = t;
        inFront = !behind;
    }
    return false;
}

// What a ray leaving the glass sees: the opaque scene within the nearby distance (when the
// nearby scene is on), else the environment, which `roughness` blurs.
vec3 lookup(vec3 P, vec3 dir, float roughness, out float hitT) {
    ivec2 hit;
    if (uNearby != 0 && marchScene(P, dir, uNearbyDistance, 24, hitT, hit))
        return texelFetch(uSceneColor, hit, 0).rgb;
    hitT = -1.0;
    return environmentRadiance(uViewToWorld * dir, roughness);
}

#endif
