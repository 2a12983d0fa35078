// Glass shading shared by the front-face pass (front.frag.glsl, the papers' two geometry passes)
// and the deferred pass (deferred.frag.glsl, after the single geometry pass): refract at the
// entry (with the normal map), find the exit point by the chosen method, refract again (TIR
// policy), look up what the exit ray sees (the nearby scene in screen space, else the
// environment) and shade with Fresnel, transmission, absorption and dispersion.
//   SIR: the entry refraction alone.
//   ISR (Wyman 2005): P2 ~ P1 + d T1, d interpolated between d_V and d_N by theta_t / theta_i.
//   DIR (Oliveira & Brauwers 2007): T1 intersected with the back-face depth map, in texture space.
#ifndef REFRACTION_GLASS_SHADING_GLSL
#define REFRACTION_GLASS_SHADING_GLSL
#include "common/material_uv.glsl"
#include "common/normal_map.glsl"
#include "refraction/glass_surface.glsl"
#include "refraction/search.glsl"

float gNormalDistance = -1.0; // ISR: d_N at this pixel in view units (-1: no far side)

const int METHOD_SIR = 1, METHOD_ISR = 2, METHOD_DIR = 3;
const int TIR_CLAMP = 0, TIR_REFLECT = 1;

uniform int uMethod, uSteps, uTirPolicy, uBounces, uDebug;
uniform int uGlassId;          // the glass's entry of glassMaterials
uniform int uSharedDispersion; // 1: one exit search shared by the channels, 0: one each
uniform float uNormalScale;
uniform sampler2D uBackDepth, uBackNormal, uFrontDepth, uFrontNormal;
uniform float uNormalLod;

layout(std430, binding = 3) readonly buffer Range { uint range[]; }; // back min/max, front min/max

struct Path {
    vec3 exitPoint;   // view space
    vec3 exitDir;     // view space, unit
    vec3 firstExit;   // P2 of the first exit search
    vec3 entryDir;    // view space: the refracted direction at the entry (T1)
    vec3 exitIncoming;// view space: the direction in the glass arriving at exitPoint ...
    vec3 exitNormal;  // ... and the surface normal there (outward)
    vec2 exitUv;
    float length;     // in glass, view units (= world units)
    bool tir;
    bool fallback;    // exit normal from the silhouette fallback
    int steps;
};

// Wyman's exit normal where P2 leaves the silhouette: T1 projected on the plane perpendicular
// to the look-at direction (view space: -z).
vec3 fallbackNormal(vec3 T1) {
    vec3 n = vec3(T1.xy, 0.0);
    return length(n) > 1e-6 ? normalize(n) : vec3(0.0, 0.0, -1.0);
}

vec3 mapNormal(sampler2D normals, vec2 uv) {
    vec3 n = textureLod(normals, uv, uNormalLod).xyz;
    return length(n) > 1e-4 ? normalize(n) : vec3(0.0);
}

Path trace(vec3 P1, vec3 V, vec3 N1, float ior) {
    Path path;
    path.tir = false;
    path.fallback = false;
    path.steps = 0;
    path.length = 0.0;
    vec3 T1;
    refractRay(V, N1, 1.0 / ior, T1); // entering the denser medium never reflects totally
    path.entryDir = T1;
    if (uMethod == METHOD_SIR) {
        path.exitPoint = P1;
        path.exitDir = T1;
        path.firstExit = P1;
        path.exitUv = projectToUv(P1);
        path.exitIncoming = T1;
        path.exitNormal = -N1;
        return path;
    }
    float zBackMin = uintBitsToFloat(range[0]), zBackMax = uintBitsToFloat(range[1]);
    vec3 P2;
    vec2 uv;
    bool valid = false;
    if (uMethod == METHOD_ISR) {
        float back = storedDepth(uBackDepth, gl_FragCoord.xy / uViewportSize);
        float dV = back > 0.0 ? max(back + P1.z, 0.0) / max(-V.z, 1e-4) : 0.0;
        float d = wymanDistance(V, N1, T1, 1.0 / ior, dV, gNormalDistance);
        P2 = P1 + d * T1;
        uv = projectToUv(P2);
        valid = storedDepth(uBackDepth, uv) > 0.0;
    } else if (T1.z < -1e-6 && zBackMax > 0.0) {
        Hit hit = searchDepthMap(uBackDepth, P1, T1, zBackMin, zBackMax, true, uSteps);
        P2 = hit.point;
        uv = hit.uv;
        valid = hit.valid;
        path.steps = hit.steps;
    } else {
        // T1 does not go deeper: it cannot meet the back surface in the depth map.
        P2 = P1;
        uv = projectToUv(P1);
    }
    vec3 No = valid ? mapNormal(uBackNormal, uv) : vec3(0.0);
    if (!valid || dot(No, T1) <= 0.0) {
        No = fallbackNormal(T1);
        path.fallback = true;
    }
    path.firstExit = P2;
    path.exitUv = uv;
    path.length = length(P2 - P1);

    vec3 dir = T1, P = P2;
    float zFrontMin = uintBitsToFloat(range[2]);
    for (int bounce = 0;; ++bounce) {
        vec3 T2;
        path.exitIncoming = dir;
        path.exitNormal = No;
        if (refractRay(dir, -No, ior, T2)) {
            path.exitPoint = P;
            path.exitDir = T2;
            return path;
        }
        path.tir = true;
        bool estimated = bounce == 0 && uMethod == METHOD_ISR; // optics.glsl
        if (uTirPolicy == TIR_CLAMP || bounce >= uBounces ||
            (estimated &&
             acos(clamp(dot(dir, No), 0.0, 1.0)) < asin(1.0 / ior) + kEstimatedTirBand)) {
            path.exitPoint = P;
            path.exitDir = tangentExit(dir, No);
            return path;
        }
        // Reflect inside and search the surface the reflected ray meets next.
        dir = reflect(dir, No);
        Hit hit;
        bool towardBack = dir.z < 0.0;
        if (towardBack && zBackMax > 0.0)
            hit = searchDepthMap(uBackDepth, P, dir, -P.z, zBackMax, true, uSteps);
        else if (!towardBack && zFrontMin > 0.0 && zFrontMin < 3.0e38)
            hit = searchDepthMap(uFrontDepth, P, dir, -P.z, zFrontMin, false, uSteps);
        else
            hit.valid = false;
        if (!hit.valid) {
            path.exitPoint = P;
            path.exitDir = dir;
            return path;
        }
        path.steps += hit.steps;
        path.length += length(hit.point - P);
        P = hit.point;
        No = towardBack ? mapNormal(uBackNormal, hit.uv) : mapNormal(uFrontNormal, hit.uv);
        if (dot(No, dir) <= 0.0)
            No = fallbackNormal(dir);
    }
}

// The glass colour at the entry point P1 (view space) with the interpolated normal N (and, for
// the normal map, the tangent and both texture coordinate sets), for the pixel at gl_FragCoord.
vec3 shadeGlass(vec3 P1, vec3 N, vec4 tangent, vec4 uvs) {
    vec3 V = normalize(P1);
    vec3 N1 = normalize(N);
    if (dot(N1, V) > 0.0)
        N1 = -N1;
    if (hasTexture(SLOT_NORMAL)) {
        vec3 mapped = perturbNormal(N1, tangent, uTexture[SLOT_NORMAL], slotUv(uvs, SLOT_NORMAL),
                                    uNormalScale);
        N1 = dot(mapped, V) < 0.0 ? mapped : N1;
    }

    GlassMaterial m = glassMaterials[uGlassId];
    vec3 ior = m.ior.rgb, sigma = m.sigma.rgb;
    float roughness = m.sigma.w;
    Path path = trace(P1, V, N1, ior.g);
    vec3 transmitted;
    bool anyTir = path.tir;
    float hitT;
    vec3 green = lookup(path.exitPoint, path.exitDir, roughness, hitT);
    bool dispersion = ior.r != ior.b;
    if (dispersion && uMethod != METHOD_SIR && uSharedDispersion != 0) {
        // One search: red and blue leave from green's exit point, each bent by its own index at
        // both interfaces, and see the scene where green's ray met it (or the environment).
        transmitted.g = green.g * exp(-sigma.g * path.length);
        for (int c = 0; c < 3; c += 2) {
            vec3 T1c;
            refractRay(V, N1, 1.0 / ior[c], T1c);
            vec3 T2c = channelExit(path.exitIncoming, -path.exitNormal, ior[c],
                                   T1c - path.entryDir, path.exitDir);
            transmitted[c] = channelSees(path.exitPoint, T2c, hitT, roughness)[c] *
                             exp(-sigma[c] * path.length);
        }
    } else if (dispersion && uMethod != 0) {
        // Each channel runs its own search with its own index of refraction.
        Path red = trace(P1, V, N1, ior.r);
        Path blue = trace(P1, V, N1, ior.b);
        float unused;
        transmitted = vec3(lookup(red.exitPoint, red.exitDir, roughness, unused).r * exp(-sigma.r * red.length),
                           green.g * exp(-sigma.g * path.length),
                           lookup(blue.exitPoint, blue.exitDir, roughness, unused).b * exp(-sigma.b * blue.length));
        anyTir = anyTir || red.tir || blue.tir;
    } else {
        transmitted = green * exp(-sigma * path.length);
    }

    vec3 color = glassColor(m, P1, V, N1, transmitted);

    float zBackMax = uintBitsToFloat(range[1]);
    float scale = zBackMax > 0.0 ? 1.0 / zBackMax : 1.0;
    // SIR has no back-face maps: its two-interface views stay black.
    int view = uMethod == METHOD_SIR && uDebug >= 1 && uDebug <= 6 ? -1 : uDebug;
    switch (view) {
    case -1: color = vec3(0.0); break;
    case 1: color = vec3(storedDepth(uBackDepth, gl_FragCoord.xy / uViewportSize) * scale); break;
    case 2: color = mapNormal(uBackNormal, gl_FragCoord.xy / uViewportSize) * 0.5 + 0.5; break;
    case 3: {
        float back = storedDepth(uBackDepth, gl_FragCoord.xy / uViewportSize);
        color = vec3(back > 0.0 ? max(back + P1.z, 0.0) * scale : 0.0);
        break;
    }
    case 4: color = vec3(max(gNormalDistance, 0.0) * scale); break;
    case 5: color = vec3(path.exitUv, path.fallback ? 1.0 : 0.0); break;
    case 6: color = vec3(float(path.steps) / float(max(uSteps, 1)), path.fallback ? 1.0 : 0.0, 0.0); break;
    case 7: color = anyTir ? vec3(1.0, 0.0, 0.0) : vec3(0.1); break;
    case 8: color = uViewToWorld * path.firstExit + uViewOriginWorld; break;
    case 9: color = uViewToWorld * path.exitDir; break;
    default: break;
    }
    return color;
}

#endif
