// Ground: a soft two-tone checker, rough dielectric, lit by the environment, fading at the edge.
#define SURFACE_LAYERS 0
#include "common/brdf.glsl"

in vec3 vWorldPosition;
out vec4 outColor;
uniform vec3 uCameraPosition;
uniform vec3 uCenter;
uniform float uHalfSize;
uniform float uTileSize;

void main() {
    vec2 cell = floor(vWorldPosition.xz / uTileSize);
    float checker = mod(cell.x + cell.y, 2.0);
    vec3 base = mix(vec3(0.30), vec3(0.42), checker);
    vec3 V = normalize(uCameraPosition - vWorldPosition);
    vec3 color = shadeMetallicRoughness(base, 0.0, 0.8, 1.0, vWorldPosition, vec3(0.0, 1.0, 0.0), V);
    outColor = vec4(color, 1.0);
}
