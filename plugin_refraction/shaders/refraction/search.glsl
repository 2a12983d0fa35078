// Ray against a perspective depth map in texture space (DIR §3.2): the search runs from S to E
// along the ray, where depth is not linear in screen space but its reciprocal is
// (alpha = (1/Pz - k1) k2, uv = ts + alpha (te - ts)), with a conservative binary search
// (DIR §3.3): each halved step advances only to a candidate whose texel is valid and that is
// still inside the surface. After k steps the parametric error is at most 2^-k.
#ifndef REFRACTION_SEARCH_GLSL
#define REFRACTION_SEARCH_GLSL

#include "refraction/view.glsl"

// Linear depth stored at uv, 0 outside the map or where no surface was drawn.
float storedDepth(sampler2D map, vec2 uv) {
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0))))
        return 0.0;
    return texelFetch(map, ivec2(uv * uViewportSize), 0).r;
}

struct Hit {
    vec3 point;   // the last accepted point, view space
    vec2 uv;      // its texture coordinate
    bool valid;   // its texel holds a surface
    int steps;    // candidates accepted
};

// Searches along P0 + t dir between the planes z = -zNear and z = -zFar (positive depths, in the
// ray's direction of travel). `back`: the map holds the far surface and the ray goes deeper;
// otherwise the near surface and the ray comes toward the camera.
Hit searchDepthMap(sampler2D map, vec3 P0, vec3 dir, float zFrom, float zTo, bool back, int steps) {
    Hit hit;
    // S and E where the ray crosses the range's planes (Eqs. 3, 4); S never before P0.
    float startDepth = back ? max(zFrom, -P0.z) : min(zFrom, -P0.z);
    vec3 S = P0 + dir * ((-startDepth - P0.z) / dir.z);
    vec3 E = P0 + dir * ((-zTo - P0.z) / dir.z);
    vec2 ts = projectToUv(S), te = projectToUv(E), dt = te - ts;
    float k1 = 1.0 / S.z;
    float k2 = abs(S.z - E.z) > 1e-9 ? S.z * E.z / (S.z - E.z) : 0.0;
    vec3 P = S, dv = E - S;
    hit.steps = 0;
    for (int i = 0; i < steps; ++i) {
        dv *= 0.5;
        float z = P.z + dv.z;
        float alpha = (1.0 / z - k1) * k2;
        float stored = storedDepth(map, ts + alpha * dt);
        bool inside = back ? (-z < stored) : (-z > stored);
        if (stored > 0.0 && inside) {
            P += dv;
            ++hit.steps;
        }
    }
    hit.point = P;
    hit.uv = ts + ((1.0 / P.z - k1) * k2) * dt;
    if (k2 == 0.0)
        hit.uv = ts;
    hit.valid = storedDepth(map, hit.uv) > 0.0;
    return hit;
}
#endif
