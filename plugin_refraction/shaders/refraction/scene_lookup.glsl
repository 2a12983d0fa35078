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

float linearDepth(float d) {
    float z = d * 2.0 - 1.0;
    return 2.0 * uNear * uFar / (uFar + uNear - z * (uFar - uNear));
}

// The texel of the depth and colour maps a clip-space point falls in (clamped to the map).
ivec2 clipTexel(vec4 C) {
    return ivec2(clamp(C.xy / C.w * 0.5 + 0.5, vec2(0.0), vec2(0.9999)) * uViewportSize);
}

// `roughness` blurs the environment.
vec3 lookup(vec3 P, vec3 dir, float roughness, out float hitT) {
    hitT = -1.0;
    if (uNearby != 0) {
        // March in clip space: the point P + t dir projects to C0 + t Cd (linear in t), so each
        // step costs a few multiply-adds, not a matrix product; depths compare in window space
        // (no division per step but the perspective one).
        vec4 C0 = uProjection * vec4(P, 1.0);
        vec4 Cd = uProjection * vec4(dir, 0.0);
        float previous = 0.0;
        // A surface is met where the ray goes from in front of the depth map to behind it, not
        // where a ray that starts behind a surface (leaving glass behind a small opaque part)
        // stays behind it, nor where it passes behind one from the side (below).
        bool inFront = C0.z / C0.w * 0.5 + 0.5 <= texelFetch(uSceneDepth, clipTexel(C0), 0).r;
        for (int i = 1; i <= 24; ++i) {
            float t = uNearbyDistance * float(i * i) / 576.0;
            vec4 C = C0 + t * Cd;
            if (C.w < uNear)
                break;
            vec3 ndc = C.xyz / C.w;
            if (any(greaterThanEqual(abs(ndc.xy), vec2(1.0))))
                break;
            vec2 uv = ndc.xy * 0.5 + 0.5;
            float d = texelFetch(uSceneDepth, ivec2(uv * uViewportSize), 0).r;
            bool behind = d < 1.0 && ndc.z * 0.5 + 0.5 > d;
            if (behind && inFront && C.w - linearDepth(d) < 0.125 * uNearbyDistance) {
                // Refine the crossing between the last step in front and this one (binary search),
                // so the lookup does not band with the step size.
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
                ivec2 hit = clipTexel(H);
                // A crossing of the surface found: the last point in front of the depth map was
                // in front of that surface too, within the refined step and the change of the
                // depth map between the two points' pixels (a surface seen at a grazing angle).
                // A ray that came from the side behind a small opaque part, from pixels of the
                // environment, was behind it already: it goes on.
                float front = texelFetch(uSceneDepth, clipTexel(L), 0).r;
                float surface = linearDepth(texelFetch(uSceneDepth, hit, 0).r);
                float slack = abs(H.w - L.w) + 0.01 * H.w +
                              (front < 1.0 ? abs(linearDepth(front) - surface) : 0.0);
                if (L.w <= surface + slack) {
                    hitT = hi;
                    return texelFetch(uSceneColor, hit, 0).rgb;
                }
            }
            previous = t;
            inFront = !behind;
        }
    }
    return environmentRadiance(uViewToWorld * dir, roughness);
}

#endif
