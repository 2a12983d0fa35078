// Grows the glass rectangle (surfaces.glsl) by the projected vertices of one glass primitive's
// deformed cage: the refined surface lies in the convex hull of its cage (subdivision masks are
// convex combinations), and so does its projection. One atomic per group and bound.
#include "common/vertex.glsl"
#include "refraction/surfaces.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Cage { DeformedVertex vertices[]; };

uniform mat4 uModelViewProjection;
uniform vec2 uViewportSize;
uniform int uVertexCount;

shared ivec4 sBounds;

void main() {
    if (gl_LocalInvocationIndex == 0u)
        sBounds = ivec4(0x7FFFFFFF, 0x7FFFFFFF, -0x7FFFFFFF, -0x7FFFFFFF);
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
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && sBounds.x <= sBounds.z) {
        atomicMin(glassRectangle[0], sBounds.x);
        atomicMin(glassRectangle[1], sBounds.y);
        atomicMax(glassRectangle[2], sBounds.z);
        atomicMax(glassRectangle[3], sBounds.w);
    }
}
