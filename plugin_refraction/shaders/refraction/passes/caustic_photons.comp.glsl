// The caustics' photons (refraction.caustic_photons, docs/materials.md "Caustics"): from each
// texel of the caustics atlas whose light meets glass (caustics.glsl's emitters), photons on the
// frame's grid follow the light's refracted path through the glass BVH (the model's crossings,
// optics.glsl: the reflected share dropped, total internal reflection followed, Beer-Lambert
// between surfaces) and land on the first opaque part or the ground square they meet in air
// after the glass. Each adds its light into the cell of the atlas that sees where it landed:
// what passed through, times the light it left with over the light the landing point gets
// unblocked (the spot's falloff, and in a perspective view the solid angle of a texel,
// cos^3 of its angle off the view's axis), over the photons a cell. A photon the light cannot
// see land (hidden behind an opaque caster) adds nothing: the shading could not show it there.
// Through dispersive glass a photon follows one channel's path, the channels in turn. Three
// programs: with CAUSTIC_GRID, the one invocation that sizes the list pass's dispatch to the
// frame's grid; with CAUSTIC_LIST, the list pass, an invocation a cell of the grid, which lists
// the cell's photons that start on an emitter (caustics.glsl); without either, the photon pass,
// an invocation a listed photon (a CPU rasteriser's SIMD lanes, or a GPU's, then all trace).
#include "common/lighting.glsl"
#include "refraction/model/optics.glsl"
#include "refraction/traced_surface.glsl"
#include "refraction/passes/caustics.glsl"
#ifndef CAUSTIC_GRID
#define CAUSTIC_GRID 0
#endif
#ifndef CAUSTIC_LIST
#define CAUSTIC_LIST 0
#endif

// The engine's shadow depth atlas, read as depths: the receivers the light sees.
layout(binding = CAUSTIC_DEPTH_UNIT) uniform sampler2D uCausticDepth;
uniform int uViewCount;
uniform int uViewLight[MAX_SHADOW_VIEWS]; // each view's light (index into punctualLights)
uniform mat4 uInverseViewProjection[MAX_SHADOW_VIEWS];
uniform vec3 uViewAxis[MAX_SHADOW_VIEWS]; // where each view looks (world, unit)
uniform int uPhotonBudget;                // the frame's photons, about

// The ground square (render::GroundPlane), a receiver: drawn, and its height, centre x and z and
// half size.
uniform int uGround;
uniform vec4 uGroundPlane;

// Where the ray from `origin` along unit `dir` (world) meets the ground square: t, or -1.
float groundDistance(vec3 origin, vec3 dir) {
    if (uGround == 0 || abs(dir.y) < 1e-9)
        return -1.0;
    float t = (uGroundPlane.x - origin.y) / dir.y;
    vec2 q = abs(origin.xz + t * dir.xz - uGroundPlane.yz);
    return t > 0.0 && max(q.x, q.y) <= uGroundPlane.w ? t : -1.0;
}

// The light of view v's light that leaves along unit `dir` into a texel of the view's image
// plane, per unit of the plane: its spot's falloff, times cos^3 of the angle off the axis (the
// solid angle of a texel) in a perspective view.
float texelLight(int v, vec3 dir) {
    PunctualLight light = punctualLights[uViewLight[v]];
    if (!perspective(shadowViews[v]))
        return 1.0;
    float c = max(dot(dir, uViewAxis[v]), 0.0);
    float spot = int(light.position.w) == LIGHT_SPOT ? spotFalloff(light, -dir) : 1.0;
    return spot * c * c * c;
}

// Adds `light` at world point X, which a photon of view `emitted` reached, into the cell of
// the view of its light that sees X; nothing where no view sees it or the light does not.
void land(int emitted, vec3 X, vec3 light, int cell) {
    PunctualLight punctual = punctualLights[uViewLight[emitted]];
    int v = shadowView(punctual, X);
    ShadowView view = shadowViews[v];
    vec4 clip = view.viewProjection * vec4(X, 1.0);
    if (clip.w <= 0.0)
        return;
    vec3 ndc = clip.xyz / clip.w;
    if (any(greaterThan(abs(ndc.xy), vec2(1.0))))
        return;
    vec2 inTile = ndc.xy * 0.5 + 0.5;
    // Hidden from the light: farther than the receiver its depth atlas sees there.
    ivec2 depthTexel = ivec2(view.tile.xy * vec2(textureSize(uCausticDepth, 0)) + 0.5) +
                       min(ivec2(inTile * view.texel.w), ivec2(view.texel.w) - 1);
    float depth = texelFetch(uCausticDepth, depthTexel, 0).r;
    float along = shadowDistance(view, X);
    if (depth < 1.0) {
        vec4 seen = uInverseViewProjection[v] * vec4(ndc.xy, depth * 2.0 - 1.0, 1.0);
        float receiver = shadowDistance(view, seen.xyz / seen.w);
        float texel = view.texel.x * (perspective(view) ? along + view.texel.z : 1.0);
        if (along > receiver + 4.0 * texel + 0.01 * along)
            return;
    }
    vec3 toX = perspective(view) ? normalize(X - view.axis.xyz) : uViewAxis[v];
    light /= max(texelLight(v, toX), 1e-3);
    // Bilinear into the tile's fine cells, the light and the photon; the light alone into the
    // coarse cell it fell in (the resolve's bilinear read smooths it).
    ivec3 tile = causticTile(shadowViews[v].tile);
    uint words[4];
    float weights[4];
    causticCells(tile.xy, tile.z, inTile * float(tile.z), cell, 0, words, weights);
    for (int k = 0; k < 4; ++k) {
        uvec4 units = uvec4(vec4(light, 1.0) * weights[k] * CAUSTIC_FIXED + 0.5);
        for (int channel = 0; channel < 4; ++channel)
            if (units[channel] != 0u)
                atomicAdd(causticSums[words[k] + uint(channel)], units[channel]);
    }
    uint coarse = causticCellWord(tile.xy, ivec2(inTile * float(tile.z)) / (cell * CAUSTIC_COARSE),
                                  cell, 1);
    uvec3 units = uvec3(light * CAUSTIC_FIXED + 0.5);
    for (int channel = 0; channel < 3; ++channel)
        if (units[channel] != 0u)
            atomicAdd(causticSums[coarse + uint(channel)], units[channel]);
}

// One photon of view v in channel `channel` (its light in `weight`, the light per texel it
// stands for), from `origin` along unit `dir`: through the glass, onto a receiver.
void photon(int v, vec3 origin, vec3 dir, int channel, vec3 weight, int cell) {
    float epsilon = 1e-5 * length(boxes[0].hi - boxes[0].lo);
    Path path;
    path.P = origin;
    path.dir = dir;
    path.weight = weight;
    path.media = uvec2(0u);
    path.ior = 1.0;
    path.sigma = vec3(0.0);
    path.roughness = 0.0;
    path.interfaces = 0;
    path.crossings = 0;
    path.splits = 0;
    int steps = 0;
    for (int k = 0; k <= MAX_PHOTON_CROSSINGS; ++k) {
        float t;
        int leaf;
        vec2 uv;
        bool hit = bvhNearest(path.P, path.dir, epsilon, 3.0e38, t, leaf, uv, steps);
        bool inAir = topMedium(path.media) == 0u;
        if (inAir && path.crossings > 0) { // the ground, where nothing is nearer
            float ground = groundDistance(path.P, path.dir);
            if (ground > 0.0 && (!hit || ground < t)) {
                land(v, path.P + ground * path.dir, path.weight, cell);
                return;
            }
        }
        if (!hit)
            return; // out to the sky
        path.weight *= exp(-path.sigma * t);
        TracedHit h = tracedHit(leaf, uv, path.dir);
        path.P += t * path.dir;
        if ((h.tag & kOpaqueTag) != 0u) { // a receiver, if the light came through glass
            if (inAir && path.crossings > 0)
                land(v, path.P, path.weight, cell);
            return;
        }
        if (k == MAX_PHOTON_CROSSINGS)
            return; // still in the glass
        SurfaceMet met = SurfaceMet((h.tag & 255u) + 1u, h.surface, h.entering);
        vec3 reflected;
        crossInterface(path, met, h.normal, channel, 0.0, true, reflected);
        if (all(lessThan(path.weight, vec3(1e-6))))
            return;
    }
}

// A hash of three numbers to a uniform number in [0, 1) (the PCG hash optics.glsl's random01
// steps by).
float causticJitter(uvec3 v) {
    uint state = v.x * 73856093u ^ v.y * 19349663u ^ v.z * 83492791u;
    return random01(state);
}

#if CAUSTIC_GRID
// The list pass's work groups for this frame's emitters, an invocation a cell of the atlas;
// the photon pass's from one.
layout(local_size_x = 1) in;
void main() {
    int cell, side;
    causticGrid(uint(uPhotonBudget), cell, side);
    ivec2 cells = (uCausticSize + cell - 1) / cell;
    listGroups[0] = uint(cells.x + 7) / 8u;
    listGroups[1] = uint(cells.y + 7) / 8u;
    listGroups[2] = 1u;
    photonCount = 0u;
    photonGroups[0] = 0u;
    photonGroups[1] = 1u;
    photonGroups[2] = 1u;
}
#else
// Where in the atlas (texels) photon `stratum` of cell `at` of the grid (cells of `cell` texels,
// side x side strata) starts: a jittered point of its stratum.
vec2 photonStart(ivec2 at, int stratum, int cell, int side) {
    uvec3 seed = uvec3(at, uint(stratum));
    vec2 jitter = vec2(causticJitter(seed), causticJitter(seed + uvec3(0u, 0u, 16u)));
    return vec2(at * cell) + float(cell) * (vec2(stratum % side, stratum / side) + jitter) /
                                 float(side);
}

#if CAUSTIC_LIST
layout(local_size_x = 8, local_size_y = 8) in;
void main() {
    int cell, side;
    causticGrid(uint(uPhotonBudget), cell, side);
    ivec2 at = ivec2(gl_GlobalInvocationID.xy), corner = at * cell;
    // Most cells see no glass: a cell of one texel is tested once, before its photons.
    if (any(greaterThanEqual(corner, uCausticSize)) || (cell == 1 && !isEmitter(corner)))
        return;
    for (int stratum = 0; stratum < side * side; ++stratum) {
        ivec2 from = ivec2(floor(photonStart(at, stratum, cell, side)));
        if (any(greaterThanEqual(from, uCausticSize)) || !isEmitter(from))
            continue;
        // At most a photon a cell, or budget photons with cells of a texel: within the list's
        // room (CausticsPass.cpp).
        uint slot = atomicAdd(photonCount, 1u);
        emitterWords[photonListStart() + slot] = photonEntry(at, stratum);
        if (slot % 64u == 0u)
            atomicAdd(photonGroups[0], 1u);
    }
}
#else
layout(local_size_x = 64) in;
void main() {
    if (gl_GlobalInvocationID.x >= photonCount)
        return;
    int cell, side;
    causticGrid(uint(uPhotonBudget), cell, side);
    ivec2 at;
    int stratum;
    photonOf(emitterWords[photonListStart() + gl_GlobalInvocationID.x], at, stratum);
    vec2 start = photonStart(at, stratum, cell, side);
    ivec2 from = ivec2(floor(start));
    int v = 0;
    ivec3 tile;
    for (; v < uViewCount; ++v) {
        tile = causticTile(shadowViews[v].tile);
        if (all(greaterThanEqual(from, tile.xy)) && all(lessThan(from, tile.xy + tile.z)))
            break;
    }
    if (v == uViewCount)
        return;
    vec2 ndc = (start - vec2(tile.xy)) / float(tile.z) * 2.0 - 1.0;
    vec4 near = uInverseViewProjection[v] * vec4(ndc, -1.0, 1.0);
    vec4 far = uInverseViewProjection[v] * vec4(ndc, 1.0, 1.0);
    vec3 origin = near.xyz / near.w, dir = normalize(far.xyz / far.w - origin);
    float leaving = (1.0 / float(side * side)) * texelLight(v, dir);
    // Its first surface: glass, or the light stops; dispersive glass splits it.
    float t;
    int leaf, steps = 0;
    vec2 uv;
    if (!bvhNearest(origin, dir, 0.0, 3.0e38, t, leaf, uv, steps))
        return;
    uint tag = triangleTags[triangleOrder[leaf]];
    if ((tag & kOpaqueTag) != 0u)
        return;
    // Dispersive glass: the photon takes one channel's path, in turn across the grid, carrying
    // three times that channel's light (the three paths' sum on average). One call of photon()
    // for both (a CPU rasteriser would run two calls' loops).
    vec3 ior = glassMaterials[tag & 255u].ior;
    int channel = 1;
    vec3 weight = vec3(leaving);
    if (ior.r != ior.b) {
        channel = (at.x + at.y + stratum) % 3;
        weight = vec3(0.0);
        weight[channel] = 3.0 * leaving;
    }
    photon(v, origin, dir, channel, weight, cell);
}
#endif
#endif
