// A glass surface where a ray traced through the glass BVH meets it (trace.glsl, and the
// caustics' photons, caustic_photons.comp.glsl): its material's factors times the frame's glass
// textures at the hit, as the capture and the reference read them.
#ifndef REFRACTION_TRACED_SURFACE_GLSL
#define REFRACTION_TRACED_SURFACE_GLSL
#include "common/normal_map.glsl"
#include "refraction/bvh.glsl"
#include "refraction/model/glass_materials.glsl"

// GLASS_TEXTURES and GLASS_NORMAL_MAPS: some glass of the frame has textures that change its
// surface, a normal map (the plugin's variants). Each texel read switches over the texture
// units, which a CPU rasteriser runs all of: a hit reads none where the frame has none.
#ifndef GLASS_TEXTURES
#define GLASS_TEXTURES 1
#endif
#ifndef GLASS_NORMAL_MAPS
#define GLASS_NORMAL_MAPS 1
#endif

// The world mesh's texture coordinates (GlassBvh::uvs) and the frame's glass textures
// (GpuState::tracedTextures: a material's TracedTextures name their units).
layout(std430, binding = WORLD_UVS_BINDING) readonly buffer WorldUvs { vec4 meshUvs[]; };
layout(binding = TRACED_TEXTURES_UNIT) uniform sampler2D uTracedTextures[TRACED_TEXTURES];

// The units the frame's glass textures take (GpuState::tracedTextures; the plugin's variants,
// all where not given): a CPU rasteriser runs every case of a switch, so a case a unit.
#ifndef TRACED_TEXTURES_USED
#define TRACED_TEXTURES_USED TRACED_TEXTURES
#endif

// Texture `t` at the hit's texture coordinates `uvs` (TEXCOORD_0 in xy, _1 in zw), its base level
// (no derivatives in the walk's loops; the reference reads level 0 too); a constant index in each
// branch, as an array of samplers requires.
vec4 tracedTexel(TracedTexture t, vec4 uvs) {
    vec3 st = vec3(t.uvSet != 0 ? uvs.zw : uvs.xy, 1.0);
    vec2 uv = vec2(dot(t.row0, st), dot(t.row1, st));
    switch (t.unit) {
#if TRACED_TEXTURES_USED > 1
    case 1: return textureLod(uTracedTextures[1], uv, 0.0);
#endif
#if TRACED_TEXTURES_USED > 2
    case 2: return textureLod(uTracedTextures[2], uv, 0.0);
#endif
#if TRACED_TEXTURES_USED > 3
    case 3: return textureLod(uTracedTextures[3], uv, 0.0);
#endif
#if TRACED_TEXTURES_USED > 4
    case 4: return textureLod(uTracedTextures[4], uv, 0.0);
#endif
#if TRACED_TEXTURES_USED > 5
    case 5: return textureLod(uTracedTextures[5], uv, 0.0);
#endif
#if TRACED_TEXTURES_USED > 6
    case 6: return textureLod(uTracedTextures[6], uv, 0.0);
#endif
#if TRACED_TEXTURES_USED > 7
    case 7: return textureLod(uTracedTextures[7], uv, 0.0);
#endif
    default: return textureLod(uTracedTextures[0], uv, 0.0);
    }
}

// Glass m's surface at a hit (its texture coordinates uvs), as the capture reads it.
GlassSurface tracedSurface(GlassMaterial m, vec4 uvs) {
    GlassSurface s = materialSurface(m);
#if GLASS_TEXTURES && GLASS_BASE_COLOR_TEXTURES
    if (m.baseColorTexture.unit >= 0)
        s.baseColor *= tracedTexel(m.baseColorTexture, uvs).rgb;
#endif
#if GLASS_TEXTURES && GLASS_TRANSMISSION_TEXTURES
    if (m.authored == 0u)
        return s;
    if (m.transmissionTexture.unit >= 0)
        s.transmission *= tracedTexel(m.transmissionTexture, uvs).r;
    if (m.metallicRoughnessTexture.unit >= 0) {
        vec4 mr = tracedTexel(m.metallicRoughnessTexture, uvs);
        s.roughness *= mr.g;
        s.metallic *= mr.b;
    }
#endif
    return s;
}

// What a ray along `along` (world) meets at BVH leaf `leaf` (barycentrics uv): the triangle's
// tag (kOpaqueTag: an opaque part's), its interpolated normal, normal-mapped on glass, the glass's
// surface there, and whether the ray enters it (by the winding, the reference's rule: against
// the outward face enters; a mirrored part's winding is reversed, as glTF places it).
struct TracedHit {
    uint tag;
    vec3 normal;
    GlassSurface surface;
    bool entering;
};

TracedHit tracedHit(int leaf, vec2 uv, vec3 along) {
    TracedHit h;
    uint triangle = triangleOrder[leaf];
    uvec3 v = uvec3(indices[3u * triangle], indices[3u * triangle + 1u], indices[3u * triangle + 2u]);
    vec3 w = vec3(1.0 - uv.x - uv.y, uv);
    h.normal = normalize(w.x * vertices[v.x].normal.xyz + w.y * vertices[v.y].normal.xyz +
                         w.z * vertices[v.z].normal.xyz);
    h.tag = triangleTags[triangle];
    bool opaque = (h.tag & kOpaqueTag) != 0u;
    if (!opaque) { // its textures as the capture and the reference read them
        GlassMaterial m = glassMaterials[h.tag & 255u];
        vec4 uvs = w.x * meshUvs[v.x] + w.y * meshUvs[v.y] + w.z * meshUvs[v.z];
        h.surface = tracedSurface(m, uvs);
#if GLASS_NORMAL_MAPS
        vec4 tangent = w.x * vertices[v.x].tangent + w.y * vertices[v.y].tangent +
                       w.z * vertices[v.z].tangent;
        if (m.normalTexture.unit >= 0 && dot(tangent.xyz, tangent.xyz) > 0.0)
            h.normal =
                perturbNormal(h.normal, tangent, tracedTexel(m.normalTexture, uvs).xyz, m.normalScale);
#endif
    }
    vec3 a = leafCorners[3 * leaf].xyz;
    vec3 face = cross(leafCorners[3 * leaf + 1].xyz - a, leafCorners[3 * leaf + 2].xyz - a);
    bool mirrored = !opaque && (h.tag & MIRRORED_TAG) != 0u;
    h.entering = (dot(face, along) < 0.0) != mirrored;
    return h;
}

#endif
