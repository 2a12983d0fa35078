// The single geometry pass (pair_gather.glsl): front and back fragments of the glass into the
// MAX-blended targets; no depth test, no culling.
#include "refraction/passes/pair_gather.glsl"
#include "refraction/passes/glass_inputs.glsl"

layout(location = 0) out vec4 outNear;
layout(location = 1) out vec4 outFar;

void main() {
    float z = -vViewPosition.z;
    vec2 n = octEncode(normalize(vViewNormal));
    uvec2 q = uvec2(quantise10(n.x), quantise10(n.y));
    if (gl_FrontFacing) {
        // d_N relative to the depth, 0 for none.
        uint d = normalDistanceCode(vNormalDistance, z, kGatheredDistanceLevels);
        outNear = vec4(kNoSurface, -z, -surfaceKey(z, q.x), -surfaceKey(z, q.y));
        outFar = vec4(kNoSurface, kNoSurface, -surfaceKey(z, d), kNoSurface);
    } else {
        outNear = vec4(z, kNoSurface, kNoSurface, kNoSurface);
        outFar = vec4(surfaceKey(z, q.x), surfaceKey(z, q.y), kNoSurface, kNoSurface);
    }
}
