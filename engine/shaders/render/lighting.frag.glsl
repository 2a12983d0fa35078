// The deferred lighting: each pixel the opaque pass covered (the depth test passes the
// full-screen triangle, at the far plane, only where a surface is nearer) shaded once from the
// surface targets (common/surface_targets.glsl) by the environment and the punctual lights,
// added to the emitted light the opaque pass left in the scene colour.
#define SURFACE_LAYERS 0
#include "common/surface_targets.glsl"

layout(location = 0) out vec4 outColor;
uniform vec3 uCameraPosition;

void main() {
    vec3 P, N;
    SurfaceMaterial m = readSurface(ivec2(gl_FragCoord.xy), P, N);
    outColor = vec4(shadeSurface(m, P, N, normalize(uCameraPosition - P)), 0.0);
}
