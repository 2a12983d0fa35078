// Draws a deformed primitive by pulling its vertices from the deform pass's buffer.
#include "common/vertex.glsl"

layout(std430, binding = VERTICES_BINDING) readonly buffer Vertices { DeformedVertex vertices[]; };
// TEXCOORD_0 in xy, _1 in zw
layout(std430, binding = UVS_BINDING) readonly buffer Uvs { vec4 uvs[]; };

uniform mat4 uModel;          // mesh node space -> world
uniform mat3 uNormalMatrix;   // inverse transpose of uModel's 3x3
uniform mat4 uViewProjection;

out vec3 vWorldPosition;
out vec3 vWorldNormal;
out vec4 vWorldTangent;
out vec4 vUv;

void main() {
    DeformedVertex v = vertices[gl_VertexID];
    vec4 world = uModel * vec4(v.position.xyz, 1.0);
    vWorldPosition = world.xyz;
    vWorldNormal = normalize(uNormalMatrix * v.normal.xyz);
    vWorldTangent = vec4(normalize(mat3(uModel) * v.tangent.xyz), v.tangent.w);
    vUv = uvs[gl_VertexID];
    gl_Position = uViewProjection * world;
}
