// Ground: the checker of common/ground.glsl over the ground square.
#define SURFACE_LAYERS 0
#include "common/ground.glsl"

in vec3 vWorldPosition;
out vec4 outColor;
uniform vec3 uCameraPosition;
uniform float uTileSize;

void main() {
    outColor = vec4(groundColor(vWorldPosition, normalize(uCameraPosition - vWorldPosition), uTileSize), 1.0);
}
