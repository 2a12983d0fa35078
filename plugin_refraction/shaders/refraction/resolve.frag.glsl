// After the single geometry pass, inside the glass rectangle: the back normals as a texture (the
// search reads their mip level 1, DIR §3.1), for TIR reflection the front depth and normals, and
// the depth mask of the shading pass: 0 where the nearest glass lies in front of the opaque scene.
#include "refraction/surfaces.glsl"

uniform sampler2D uGatherNear, uGatherFar, uSceneDepth;
uniform float uNear, uFar;

layout(location = 0) out vec4 outBackNormal;
layout(location = 1) out float outFrontDepth;
layout(location = 2) out vec4 outFrontNormal;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 near = texelFetch(uGatherNear, p, 0);
    vec4 far = texelFetch(uGatherFar, p, 0);
    bool back = near.x > 0.0, front = near.y > 0.5 * kNoSurface;
    float z = -near.y;
    outBackNormal = back ? vec4(octDecodePayload(far.x, far.y), 1.0) : vec4(0.0);
    outFrontDepth = front ? z : 0.0;
    outFrontNormal = front ? vec4(octDecodePayload(near.z, near.w), 1.0) : vec4(0.0);
    float scene = texelFetch(uSceneDepth, p, 0).r;
    float sceneZ = 2.0 * uNear * uFar / (uFar + uNear - (scene * 2.0 - 1.0) * (uFar - uNear));
    gl_FragDepth = front && (scene >= 1.0 || z <= sceneZ) ? 0.0 : 1.0;
}
