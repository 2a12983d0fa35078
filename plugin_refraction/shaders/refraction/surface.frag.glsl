// Back faces (DIR §3.1, ISR §3.2) or front faces (for TIR reflection): linear view depth
// (positive) and the outward view-space normal of the kept surface. Texels no surface covers
// keep the clear value 0 (invalid).
#include "refraction/glass_inputs.glsl"

layout(location = 0) out float outDepth;
layout(location = 1) out vec4 outNormal;

void main() {
    outDepth = -vViewPosition.z;
    // Interpolated normals point outward; a back face's normal points away from the camera.
    outNormal = vec4(normalize(vViewNormal), 1.0);
}
