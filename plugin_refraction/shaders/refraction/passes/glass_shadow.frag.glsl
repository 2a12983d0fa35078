// A glass fragment as a light sees it (refraction.glass_shadow): what it takes from the light
// going straight through, as optical depth (-ln of what passes) added into its texel of the
// engine's glass atlas, and its distance along the light's ray, of which the atlas keeps the
// nearest (common/shadows.glsl reads both). A surface facing the light lets (1 - F) of it in,
// through its tint and transmission, and starts its absorption; one facing away lets (1 - F)
// out and ends it: summed over a closed surface, sigma times the length inside. F is the
// entering reflectance at the light's angle to the surface (optics.glsl), at both crossings.
// With CAUSTIC_EMITTERS, it also marks each texel of the caustics atlas whose light meets glass,
// where the photon pass emits (caustics.glsl).
#include "refraction/passes/fragment_surface.glsl"
#include "refraction/model/optics.glsl"
#ifndef CAUSTIC_EMITTERS
#define CAUSTIC_EMITTERS 0
#endif
#if CAUSTIC_EMITTERS
#include "refraction/passes/caustics.glsl"
#endif

uniform int uGlassId;
uniform int uPerspective; // the view is a spot's or a point light's (else a directional one's)
uniform float uNear;      // its near plane's distance, where the atlas's distances start

layout(location = 0) out vec4 outGlass;

void main() {
    uint id = uint(uGlassId);
    GlassMaterial m = glassMaterials[id];
#if GLASS_TEXTURES
    GlassSurface s = fragmentSurface(id);
#else // no glass of the frame has textures that change its surface
    GlassSurface s = materialSurface(m);
#endif
    vec3 n = fragmentNormal();
    vec3 toLight = uPerspective != 0 ? -normalize(vViewPosition) : vec3(0.0, 0.0, 1.0);
    float d = (uPerspective != 0 ? length(vViewPosition) : -vViewPosition.z) - uNear;
    float cosI = clamp(abs(dot(n, toLight)), 1e-4, 1.0);
    vec3 through = 1.0 - reflectance(m, s, cosI, 1.0 / m.ior.g);
    if (gl_FrontFacing)
        through *= s.baseColor * (1.0 - s.metallic) * s.transmission;
    vec3 depth = -log(max(through, vec3(1e-6)));
    depth += gl_FrontFacing ? -m.sigma * d : m.sigma * d;
    outGlass = vec4(depth, d);
#if CAUSTIC_EMITTERS
    ivec2 texel = ivec2(gl_FragCoord.xy) / CAUSTIC_SCALE;
    uint i = causticTexelIndex(texel), bit = 1u << (i % 32u);
    // A plain read first: most of a texel's fragments find its bit set, and skip the atomic.
    if ((emitterWords[i / 32u] & bit) == 0u && (atomicOr(emitterWords[i / 32u], bit) & bit) == 0u)
        atomicAdd(emitterCount, 1u); // the texel's first glass
#endif
}
