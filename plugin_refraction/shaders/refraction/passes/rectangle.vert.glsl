// The glass rectangle (glass_extent.glsl) as two triangles, for the full-screen passes that only
// matter where the glass is; an empty rectangle draws nothing.
#include "refraction/passes/glass_extent.glsl"

uniform vec2 uViewportSize;
uniform float uRectangleMargin; // pixels added around it (0 unless set)

void main() {
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    vec2 lo = vec2(glassPixelMin[0], glassPixelMin[1]);
    vec2 hi = vec2(glassPixelMax[0], glassPixelMax[1]) + 1.0;
    if (any(greaterThan(lo, hi))) {
        hi = lo; // empty
    } else {
        lo = max(lo - uRectangleMargin, vec2(0.0));
        hi = min(hi + uRectangleMargin, uViewportSize);
    }
    vec2 pixel = mix(lo, hi, corners[gl_VertexID]);
    gl_Position = vec4(pixel / uViewportSize * 2.0 - 1.0, 1.0, 1.0);
}
