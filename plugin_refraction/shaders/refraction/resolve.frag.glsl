// Unpacks the single geometry pass into the maps the searches read: back depth and normal, front
// depth (with d_N) and normal; 0 where no surface was drawn. Also starts the composite: the
// scene colour everywhere, and a depth mask (0 where the nearest glass is in front of the opaque
// scene, else 1) so that the shading pass runs only there (early depth test).
#include "refraction/surfaces.glsl"

uniform sampler2D uGatherNear, uGatherFar, uSceneColor, uSceneDepth;
uniform float uNear, uFar;

layout(location = 0) out float outBackDepth;
layout(location = 1) out vec4 outBackNormal;
layout(location = 2) out vec2 outFront; // depth, d_N (-1: none)
layout(location = 3) out vec4 outFrontNormal;
layout(location = 4) out vec4 outColor;

vec3 payloadNormal(float keyX, float keyY) {
    return octDecode(vec2(keyPayload(keyX), keyPayload(keyY)) / 1023.0);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 near = texelFetch(uGatherNear, p, 0);
    vec4 far = texelFetch(uGatherFar, p, 0);
    bool front = near.x > 0.5 * kNoSurface, back = near.y > 0.5 * kNoSurface;
    outBackDepth = back ? near.y : 0.0;
    outBackNormal = back ? vec4(payloadNormal(far.x, far.y), 1.0) : vec4(0.0);
    uint d = keyPayload(far.z);
    float z = -near.x;
    outFront = front ? vec2(z, d == 0u ? -1.0 : float(d - 1u) / 1022.0 * z) : vec2(0.0);
    outFrontNormal = front ? vec4(payloadNormal(near.z, near.w), 1.0) : vec4(0.0);
    outColor = vec4(texelFetch(uSceneColor, p, 0).rgb, 1.0);
    float scene = texelFetch(uSceneDepth, p, 0).r;
    float sceneZ = 2.0 * uNear * uFar / (uFar + uNear - (scene * 2.0 - 1.0) * (uFar - uNear));
    gl_FragDepth = front && (scene >= 1.0 || z <= sceneZ) ? 0.0 : 1.0;
}
