// Draws a deformed primitive by pulling its vertices from the deform pass's buffer; where the
// frame accumulates, also where the vertex was on the previous frame (the deformation the
// previous frame left, placed as it was then) for its motion (common/motion.glsl).
#include "common/motion.glsl"
#include "common/vertex.glsl"

layout(std430, binding = VERTICES_BINDING) readonly buffer Vertices { DeformedVertex vertices[]; };
layout(std430, binding = PREVIOUS_VERTICES_BINDING) readonly buffer PreviousVertices {
    DeformedVertex previousVertices[];
};
// TEXCOORD_0 in xy, _1 in zw
layout(std430, binding = UVS_BINDING) readonly buffer Uvs { vec4 uvs[]; };

uniform mat4 uModel;          // mesh node space -> world
uniform mat3 uNormalMatrix;   // inverse transpose of uModel's 3x3
uniform mat4 uViewProjection;
uniform mat4 uPreviousModel;  // uModel on the previous frame

out vec3 vWorldPosition;
out vec3 vWorldNormal;
out vec4 vWorldTangent;
out vec4 vUv;
out vec4 vClip, vPreviousClip; // unjittered, this frame and the previous one

void main() {
    DeformedVertex v = vertices[gl_VertexID];
    vec4 world = uModel * vec4(v.position.xyz, 1.0);
    vWorldPosition = world.xyz;
    vWorldNormal = normalize(uNormalMatrix * v.normal.xyz);
    vWorldTangent = vec4(normalize(mat3(uModel) * v.tangent.xyz), v.tangent.w);
    vUv = uvs[gl_VertexID];
    vClip = vPreviousClip = vec4(0.0, 0.0, 0.0, 1.0);
    if (writesMotion()) {
        vClip = uMotionViewProjection * world;
        vPreviousClip = uPreviousViewProjection * uPreviousModel *
                        vec4(previousVertices[gl_VertexID].position.xyz, 1.0);
    }
    gl_Position = uViewProjection * world;
}
