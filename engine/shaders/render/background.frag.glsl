// The environment behind everything: the view ray of each pixel looked up in the environment.
// (Where the frame accumulates, its motion is the motion target's clear value: common/motion.glsl.)
#include "common/environment.glsl"

in vec2 vUv;
layout(location = 0) out vec4 outColor;
uniform mat4 uInverseViewProjection;
uniform float uBackgroundBlur; // roughness of the lookup (0: sharp)

void main() {
    vec4 far = uInverseViewProjection * vec4(vUv * 2.0 - 1.0, 1.0, 1.0);
    vec4 near = uInverseViewProjection * vec4(vUv * 2.0 - 1.0, -1.0, 1.0);
    vec3 direction = normalize(far.xyz / far.w - near.xyz / near.w);
    outColor = vec4(environmentRadiance(direction, uBackgroundBlur), 1.0);
}
