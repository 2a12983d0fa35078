// The pair capture resolved over the glass rectangle (the papers' two-surface model as a capture
// of the one walk, surfaces=two-surface): each pixel's nearest front surface as its layer 0 and
// its back surface as layer 1 (layers.glsl: their attributes in the layer arrays, their depths
// in the first depth map, 3e38 where absent), the depth ranges the papers' search is bounded by
// (pair_ranges.glsl), and the walk's mask: 0 where the front lies before the opaque scene.
//   PAIR_GATHERED 1: from the one MAX-blended geometry pass (pair_gather.glsl), also writing the
//     normals as the maps the papers' search reads mip-filtered (DIR §3.1);
//   PAIR_GATHERED 0: from the two depth-tested passes (pair_surface.frag.glsl), whose normal maps
//     are those maps already; with textured glass in the frame (GLASS_TEXTURES) also their
//     surfaces, into the layers' (never gathered: the one pass reads no texture).
#include "common/motion.glsl"
#include "refraction/passes/layers.glsl"
#include "refraction/passes/pair_gather.glsl"
#include "refraction/passes/pair_ranges.glsl"

layout(binding = SCENE_DEPTH_UNIT) uniform sampler2D uSceneDepth;
uniform float uNear, uFar;

layout(location = 0) out vec4 outDepths0;

struct Surface {
    bool present;
    float z, normalDistance; // view depth; d_N in view units, -1: none
    vec3 normal;
    uint glass;
};

#if PAIR_GATHERED
layout(binding = PAIR_MAPS_UNIT) uniform sampler2D uGatherNear;
layout(binding = PAIR_MAPS_UNIT + 1) uniform sampler2D uGatherFar;
uniform int uGlassId; // one pass serves one glass
layout(location = 1) out vec4 outFrontNormal;
layout(location = 2) out vec4 outBackNormal;

void readPair(ivec2 p, out Surface front, out Surface back) {
    vec4 near = texelFetch(uGatherNear, p, 0), far = texelFetch(uGatherFar, p, 0);
    front.present = near.y > 0.5 * kNoSurface;
    front.z = -near.y;
    front.normal = octDecodePayload(near.z, near.w);
    front.normalDistance = normalDistanceOf(keyPayload(far.z), front.z, kGatheredDistanceLevels);
    back.present = near.x > 0.0;
    back.z = near.x;
    back.normal = octDecodePayload(far.x, far.y);
    back.normalDistance = -1.0;
    front.glass = back.glass = uint(uGlassId);
    outFrontNormal = front.present ? vec4(front.normal, 1.0) : vec4(0.0);
    outBackNormal = back.present ? vec4(back.normal, 1.0) : vec4(0.0);
}
#else
layout(binding = PAIR_MAPS_UNIT) uniform sampler2D uFrontDepth;
layout(binding = PAIR_MAPS_UNIT + 1) uniform sampler2D uFrontNormal;
layout(binding = PAIR_MAPS_UNIT + 2) uniform sampler2D uBackDepth;
layout(binding = PAIR_MAPS_UNIT + 3) uniform sampler2D uBackNormal;
#if GLASS_TEXTURES
layout(binding = PAIR_SURFACES_UNIT) uniform usampler2D uFrontSurface;
layout(binding = PAIR_SURFACES_UNIT + 1) uniform usampler2D uBackSurface;
#endif

Surface readSurface(sampler2D depth, sampler2D normal, ivec2 p) {
    vec2 d = texelFetch(depth, p, 0).xy;
    vec4 n = texelFetch(normal, p, 0);
    return Surface(n.w > 0.5, d.x, d.y, normalize(n.xyz + vec3(0.0, 0.0, 1e-12)), uint(n.w - 0.5));
}

void readPair(ivec2 p, out Surface front, out Surface back) {
    front = readSurface(uFrontDepth, uFrontNormal, p);
    back = readSurface(uBackDepth, uBackNormal, p);
    if (writesMotion()) // the front's motion (the front pass's depth target, z and w)
        layerMotion[pixelIndex(p) * 2u] = packHalf2x16(texelFetch(uFrontDepth, p, 0).zw);
#if GLASS_TEXTURES
    uint pixel = pixelIndex(p);
    layerSurface[pixel * 2u] = texelFetch(uFrontSurface, p, 0).xy;
    layerSurface[pixel * 2u + 1u] = texelFetch(uBackSurface, p, 0).xy;
#endif
}
#endif

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    Surface front, back;
    readPair(p, front, back);
    uint pixel = pixelIndex(p);
    uint d = normalDistanceCode(front.normalDistance, front.z, kLayerDistanceLevels);
    layerHeads[pixel] = uint(front.present) + uint(back.present);
    layerAttr[pixel * 2u] = uvec2(packOctNormal(front.normal), front.glass | kLayerFront | (d << 16));
    layerAttr[pixel * 2u + 1u] = uvec2(packOctNormal(back.normal), back.glass);
    outDepths0 = vec4(front.present ? front.z : NO_DEPTH, back.present ? back.z : NO_DEPTH,
                      NO_DEPTH, NO_DEPTH);
    if (back.present) {
        atomicMin(pairBackRange[0], floatBitsToUint(back.z));
        atomicMax(pairBackRange[1], floatBitsToUint(back.z));
    }
    if (front.present)
        atomicMin(pairFrontMin, floatBitsToUint(front.z));
    float scene = texelFetch(uSceneDepth, p, 0).r;
    gl_FragDepth =
        front.present && (scene >= 1.0 || front.z <= viewDepthOf(scene, uNear, uFar)) ? 0.0 : 1.0;
}
