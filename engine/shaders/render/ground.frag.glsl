// Ground: the checker of common/ground.glsl over the ground square; where the frame accumulates
// (uWriteMotion), its motion too: a still world point's.
#define SURFACE_LAYERS 0
#include "common/ground.glsl"
#include "common/motion.glsl"

in vec3 vWorldPosition;
layout(location = 0) out vec4 outColor;
layout(location = 1) out uvec4 outMotion;
uniform vec3 uCameraPosition;
uniform float uTileSize;

void main() {
    vec3 V = normalize(uCameraPosition - vWorldPosition);
    outColor = vec4(groundColor(vWorldPosition, V, uTileSize), 1.0);
    if (writesMotion()) {
        float depth = (uMotionViewProjection * vec4(vWorldPosition, 1.0)).w;
        float previous = (uPreviousViewProjection * vec4(vWorldPosition, 1.0)).w;
        outMotion = packMotion(motionIdentity(MOTION_GROUND, 0u),
                               pointMotion(vWorldPosition, vWorldPosition), depth, previous, 0u);
    }
}
