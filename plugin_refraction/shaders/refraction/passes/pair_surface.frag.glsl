// The pair capture drawn as the papers' two geometry passes (geometry-passes=two, and wherever
// one MAX-blended pass cannot serve): the back faces (the farthest, or the nearest with
// back-surface=first) and the nearest front faces, each under its own depth test. Per texel:
// linear view depth and d_N (-1: none) (where the frame accumulates, the surface's motion in
// the target's z and w: common/motion.glsl), and the outward view normal after the normal map with
// the glass id + 1 in w (0: no surface, the clear value); with textured glass in the frame
// (GLASS_TEXTURES), the glass surface there (packSurface). pair_resolve.frag.glsl reads them.
#include "common/motion.glsl"
#include "refraction/passes/fragment_surface.glsl"

uniform int uGlassId;

layout(location = 0) out vec4 outDepth;
layout(location = 1) out vec4 outNormal;
#if GLASS_TEXTURES
layout(location = 2) out uvec2 outSurface;
#endif

void main() {
    vec3 n = fragmentNormal();
    outDepth = vec4(-vViewPosition.z, vNormalDistance,
                    writesMotion() ? clipToPixel(vClip) - clipToPixel(vPreviousClip) : vec2(0.0));
    outNormal = vec4(n, float(uGlassId + 1));
#if GLASS_TEXTURES
    outSurface = packSurface(fragmentSurface(uint(uGlassId)));
#endif
}
