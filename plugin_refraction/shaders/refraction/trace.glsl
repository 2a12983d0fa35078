// The walk's traced crossings (method trace, and the hybrid's handed-over pixels): the exact
// next interface of a ray in the glass BVH (bvh.glsl) with its normal-mapped normal, and the
// entry of a camera ray. Included by walk.glsl after its Crossing, layers and materials.
#ifndef REFRACTION_TRACE_GLSL
#define REFRACTION_TRACE_GLSL
#include "refraction/bvh.glsl"

#include "common/normal_map.glsl"
int gTraceRays = 0, gTraceSteps = 0; // this invocation's rays and BVH nodes visited
// The world mesh's texture coordinates (GlassBvh::uvs) and the frame's glass textures
// (GpuState::tracedTextures: a material's TracedTextures name their units).
layout(std430, binding = WORLD_UVS_BINDING) readonly buffer WorldUvs { vec4 meshUvs[]; };
layout(binding = TRACED_TEXTURES_UNIT) uniform sampler2D uTracedTextures[TRACED_TEXTURES];

// Texture `t` at the hit's texture coordinates `uvs` (TEXCOORD_0 in xy, _1 in zw), its base level
// (no derivatives in the walk's loops; the reference reads level 0 too); a constant index in each
// branch, as an array of samplers requires.
vec4 tracedTexel(TracedTexture t, vec4 uvs) {
    vec3 st = vec3(t.uvSet != 0 ? uvs.zw : uvs.xy, 1.0);
    vec2 uv = vec2(dot(t.row0, st), dot(t.row1, st));
    switch (t.unit) {
    case 0: return textureLod(uTracedTextures[0], uv, 0.0);
    case 1: return textureLod(uTracedTextures[1], uv, 0.0);
    case 2: return textureLod(uTracedTextures[2], uv, 0.0);
    case 3: return textureLod(uTracedTextures[3], uv, 0.0);
    case 4: return textureLod(uTracedTextures[4], uv, 0.0);
    case 5: return textureLod(uTracedTextures[5], uv, 0.0);
    case 6: return textureLod(uTracedTextures[6], uv, 0.0);
    default: return textureLod(uTracedTextures[7], uv, 0.0);
    }
}

// Glass m's surface at a hit (its texture coordinates uvs), as the capture reads it.
GlassSurface tracedSurface(GlassMaterial m, vec4 uvs) {
    GlassSurface s = materialSurface(m);
    if (m.baseColorTexture.unit >= 0)
        s.baseColor *= tracedTexel(m.baseColorTexture, uvs).rgb;
    if (m.authored == 0u)
        return s;
    if (m.transmissionTexture.unit >= 0)
        s.transmission *= tracedTexel(m.transmissionTexture, uvs).r;
    if (m.metallicRoughnessTexture.unit >= 0) {
        vec4 mr = tracedTexel(m.metallicRoughnessTexture, uvs);
        s.roughness *= mr.g;
        s.metallic *= mr.b;
    }
    return s;
}

// The exact next interface: the ray traced through the glass BVH (world space), the triangle's
// interpolated normal, its glass, its surface there and which way the ray crosses it (by the
// winding, the reference's rule: against the outward face enters); or the opaque part it
// meets first.
Crossing traceCrossing(vec3 P, vec3 dir) {
    Crossing c = noCrossing(P, false);
    vec3 origin = uViewToWorld * P + uViewOriginWorld, along = uViewToWorld * dir;
    float epsilon = 1e-5 * length(boxes[0].hi - boxes[0].lo), t;
    int leaf;
    vec2 uv;
    ++gTraceRays;
    if (!bvhNearest(origin, along, epsilon, 3.0e38, t, leaf, uv, gTraceSteps))
        return c;
    uint triangle = triangleOrder[leaf];
    uvec3 v = uvec3(indices[3u * triangle], indices[3u * triangle + 1u], indices[3u * triangle + 2u]);
    vec3 w = vec3(1.0 - uv.x - uv.y, uv);
    vec3 n = normalize(w.x * vertices[v.x].normal.xyz + w.y * vertices[v.y].normal.xyz +
                       w.z * vertices[v.z].normal.xyz);
    uint tag = triangleTags[triangle];
    bool opaque = (tag & kOpaqueTag) != 0u;
    if (!opaque) { // its textures as the capture and the reference read them
        GlassMaterial m = glassMaterials[tag & 255u];
        vec4 uvs = w.x * meshUvs[v.x] + w.y * meshUvs[v.y] + w.z * meshUvs[v.z];
        c.surface = tracedSurface(m, uvs);
        vec4 tangent = w.x * vertices[v.x].tangent + w.y * vertices[v.y].tangent +
                       w.z * vertices[v.z].tangent;
        if (m.normalTexture.unit >= 0 && dot(tangent.xyz, tangent.xyz) > 0.0)
            n = perturbNormal(n, tangent, tracedTexel(m.normalTexture, uvs).xyz, m.normalScale);
    }
    vec3 a = leafCorners[3 * leaf].xyz;
    vec3 face = cross(leafCorners[3 * leaf + 1].xyz - a, leafCorners[3 * leaf + 2].xyz - a);
    // Against the outward face enters; a mirrored part's winding is reversed (glTF).
    bool mirrored = !opaque && (tag & MIRRORED_TAG) != 0u;
    bool entering = (dot(face, along) < 0.0) != mirrored;
    c.found = true;
    c.point = P + dir * max(t - epsilon, 0.0);
    c.beyond = P + dir * (t + epsilon);
    c.attr = uvec2(packOctNormal(transpose(uViewToWorld) * n),
                   opaque ? tag : (tag & 255u) | (entering ? kLayerFront : 0u));
    return c;
}

// Whether the crossing is an opaque part's (its attr.y the part's tag).
bool tracedOpaque(Crossing c) {
    return (c.attr.y & kOpaqueTag) != 0u;
}

// What a traced ray sees where it meets an opaque part: its material shaded there by the tag's
// factors as the frame shades an untextured surface (common/brdf.glsl); for a textured part the
// frame's colour where the frame shows that point (its texture, though seen from the camera:
// on the untextured core of a glass sphere that cost 5 dB against shading it).
vec3 opaqueSeen(Crossing c, vec3 dir) {
    uint tag = c.attr.y;
    vec2 uv = projectToUv(c.beyond);
    if ((tag & kOpaqueTextured) != 0u && all(greaterThanEqual(uv, vec2(0.0))) &&
        all(lessThan(uv, vec2(1.0)))) {
        ivec2 pixel = ivec2(uv * uViewportSize);
        if (abs(sceneDepthAt(pixel) + c.beyond.z) < 0.01 * -c.beyond.z)
            return texelFetch(uSceneColor, pixel, 0).rgb;
    }
    vec3 base = vec3(uvec3(tag, tag >> 7, tag >> 14) & 127u) / 127.0;
    float roughness = float((tag >> 21) & 31u) / 31.0, metallic = float((tag >> 26) & 15u) / 15.0;
    vec3 N = uViewToWorld * layerNormal(c.attr), V = -(uViewToWorld * dir);
    return shadeMetallicRoughness(base * base, metallic, roughness, 1.0,
                                  uViewToWorld * c.point + uViewOriginWorld,
                                  dot(N, V) < 0.0 ? -N : N, V);
}

// The entry of a camera ray along view direction V, traced: false where it meets no glass before
// the opaque scene at pixel p (the sample sees what lies behind the glass there).
bool traceEntry(vec3 V, ivec2 p, out vec3 P1, out uvec2 attr, out GlassSurface surface) {
    Crossing c = traceCrossing(vec3(0.0), V);
    P1 = 0.5 * (c.point + c.beyond); // on the surface: the refracted ray does not meet it again
    attr = c.attr;
    surface = c.surface;
    return c.found && !tracedOpaque(c) && -c.point.z < sceneDepthAt(p);
}
#endif
