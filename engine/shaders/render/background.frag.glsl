// The environment behind everything: the view ray of each pixel looked up in the environment;
// where the frame accumulates (uWriteMotion), its motion too: the camera's turn alone.
#include "common/environment.glsl"
#include "common/motion.glsl"

in vec2 vUv;
layout(location = 0) out vec4 outColor;
layout(location = 1) out uvec4 outMotion;
uniform mat4 uInverseViewProjection;
uniform float uBackgroundBlur; // roughness of the lookup (0: sharp)

void main() {
    vec4 far = uInverseViewProjection * vec4(vUv * 2.0 - 1.0, 1.0, 1.0);
    vec4 near = uInverseViewProjection * vec4(vUv * 2.0 - 1.0, -1.0, 1.0);
    vec3 direction = normalize(far.xyz / far.w - near.xyz / near.w);
    outColor = vec4(environmentRadiance(direction, uBackgroundBlur), 1.0);
    if (uWriteMotion != 0)
        outMotion = packMotion(motionIdentity(MOTION_ENVIRONMENT, 0u), directionMotion(direction),
                               0.0, 0.0, 0u);
}
