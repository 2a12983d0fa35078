// The walk's traced crossings (method trace, and the hybrid's handed-over pixels): the exact
// next interface of a ray in the glass BVH (bvh.glsl) with its normal-mapped normal, and the
// entry of a camera ray. Included by walk.glsl after its Crossing, layers and materials.
#ifndef REFRACTION_TRACE_GLSL
#define REFRACTION_TRACE_GLSL
#include "refraction/traced_surface.glsl"

int gTraceRays = 0, gTraceSteps = 0; // this invocation's rays and BVH nodes visited
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
    TracedHit h = tracedHit(leaf, uv, along);
    bool opaque = (h.tag & kOpaqueTag) != 0u;
    if (!opaque)
        c.surface = h.surface;
    c.found = true;
    c.point = P + dir * max(t - epsilon, 0.0);
    c.beyond = P + dir * (t + epsilon);
    c.attr = uvec2(packOctNormal(transpose(uViewToWorld) * h.normal),
                   opaque ? h.tag : (h.tag & 255u) | (h.entering ? kLayerFront : 0u));
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
