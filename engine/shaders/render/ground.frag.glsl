// Ground: the checker of common/ground.glsl over the ground square.
#define SURFACE_LAYERS 0
#include "common/ground.glsl"

in vec3 vWorldPosition;
out vec4 outColor;
uniform vec3 uCameraPosition;
uniform float uTileSize;

void main() {
    vec3 V = normalize(uCameraPosition - vWorldPosition);
    outColor = vec4(groundColor(vWorldPosition, V, uTileSize), 1.0);
}
