// The surface targets, the deferred shading's G-buffer: for each pixel, the nearest opaque
// surface the opaque pass drew (render/opaque.frag.glsl) as its world position, shading normal
// and core material (common/brdf.glsl's SurfaceMaterial without layers), which the lighting pass
// (render/lighting.frag.glsl) shades once. A CPU rasteriser shades every fragment of a small
// triangle's quads and every hidden one; this way the lights, the environment and the shadow
// lookups are paid once per covered pixel. The surface's emitted light is in the scene colour
// already; the lighting pass adds to it.
// A writer defines DEFERRED 1 before it includes this file; the lighting pass includes it
// without. render::passes::addOpaque creates the targets.
#ifndef COMMON_SURFACE_TARGETS_GLSL
#define COMMON_SURFACE_TARGETS_GLSL
#include "common/brdf.glsl"
#ifndef DEFERRED
#define DEFERRED 0
#endif

#if DEFERRED
// Colour attachments 1-4; the scene colour is 0 and the motion, where the frame accumulates, 5.
layout(location = 1) out vec4 outSurfacePosition; // world xyz (RGBA32F); occlusion
layout(location = 2) out vec4 outSurfaceNormal;   // unit shading normal (RGBA32F); roughness
layout(location = 3) out vec4 outSurfaceBase;     // base colour (RGBA16F); metallic
layout(location = 4) out vec4 outSurfaceSpecular; // dielectric F0 (RGBA16F); specular weight
#define MOTION_TARGET 5 // the writer's outMotion

void writeSurface(vec3 P, vec3 N, SurfaceMaterial m) {
    outSurfacePosition = vec4(P, m.occlusion);
    outSurfaceNormal = vec4(N, m.roughness);
    outSurfaceBase = vec4(m.baseColor, m.metallic);
    outSurfaceSpecular = vec4(m.dielectricF0, m.specularWeight);
}
#else
// Bound at the material's units: the lighting pass draws no material.
layout(binding = MATERIAL_UNIT) uniform sampler2D uSurfaces[4];

// The surface at `pixel`: its material, world position P and shading normal N.
SurfaceMaterial readSurface(ivec2 pixel, out vec3 P, out vec3 N) {
    vec4 position = texelFetch(uSurfaces[0], pixel, 0);
    vec4 normal = texelFetch(uSurfaces[1], pixel, 0);
    vec4 base = texelFetch(uSurfaces[2], pixel, 0);
    vec4 specular = texelFetch(uSurfaces[3], pixel, 0);
    P = position.xyz;
    N = normal.xyz;
    SurfaceMaterial m = coreSurface(base.rgb, base.a, normal.a, position.a, N);
    m.dielectricF0 = specular.rgb;
    m.specularWeight = specular.a;
    return m;
}
#endif
#endif
