// The glass_extent pass: grows the glass extent (glass_extent.glsl) by the projected vertices of
// one glass primitive's deformed cage, a dispatch a primitive. The refined surface lies in the
// convex hull of its cage (subdivision masks are convex combinations), and so does its
// projection. One atomic per group and bound. The view-space box of the vertices too (where
// the walk's searches end).
#include "common/vertex.glsl"
#include "refraction/passes/glass_extent.glsl"

layout(local_size_x = 64) in;

// the primitive's deformed cage
layout(std430, binding = VERTICES_BINDING) readonly buffer Vertices { DeformedVertex vertices[]; };

uniform mat4 uModelViewProjection;
uniform mat4 uModelView;
uniform vec2 uViewportSize;
uniform int uVertexCount;

shared ivec4 sBounds;
shared int sBox[6]; // view-space min x, y, z, max x, y, z (ordered)

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        sBounds = ivec4(0x7FFFFFFF, 0x7FFFFFFF, -0x7FFFFFFF, -0x7FFFFFFF);
        for (int c = 0; c < 3; ++c) {
            sBox[c] = 0x7FFFFFFF;
            sBox[3 + c] = -0x7FFFFFFF;
        }
    }
    barrier();
    uint v = gl_GlobalInvocationID.x;
    if (v < uint(uVertexCount)) {
        vec4 clip = uModelViewProjection * vec4(vertices[v].position.xyz, 1.0);
        // Conservative: a vertex behind the eye could project anywhere, so take the screen.
        vec2 lo = vec2(0.0), hi = uViewportSize - 1.0;
        if (clip.w > 0.0) {
            vec2 pixel = (clip.xy / clip.w * 0.5 + 0.5) * uViewportSize;
            lo = clamp(floor(pixel) - 1.0, vec2(0.0), uViewportSize - 1.0);
            hi = clamp(ceil(pixel) + 1.0, vec2(0.0), uViewportSize - 1.0);
        }
        atomicMin(sBounds.x, int(lo.x));
        atomicMin(sBounds.y, int(lo.y));
        atomicMax(sBounds.z, int(hi.x));
        atomicMax(sBounds.w, int(hi.y));
        vec3 view = (uModelView * vec4(vertices[v].position.xyz, 1.0)).xyz;
        for (int c = 0; c < 3; ++c) {
            atomicMin(sBox[c], floatToOrdered(view[c]));
            atomicMax(sBox[3 + c], floatToOrdered(view[c]));
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && sBounds.x <= sBounds.z) {
        atomicMin(glassPixelMin[0], sBounds.x);
        atomicMin(glassPixelMin[1], sBounds.y);
        atomicMax(glassPixelMax[0], sBounds.z);
        atomicMax(glassPixelMax[1], sBounds.w);
        for (int c = 0; c < 3; ++c) {
            atomicMin(glassBoxMin[c], sBox[c]);
            atomicMax(glassBoxMax[c], sBox[3 + c]);
        }
    }
}
