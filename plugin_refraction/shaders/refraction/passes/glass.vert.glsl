// Glass surfaces: pulls the deformed vertex (and, for ISR, its per-frame d_N) and passes
// view-space position, normal and tangent on; where the frame accumulates, the vertex's clip
// position now and on the previous frame for its motion (common/motion.glsl).
#include "common/motion.glsl"
#include "common/vertex.glsl"

layout(std430, binding = VERTICES_BINDING) readonly buffer Vertices { DeformedVertex vertices[]; };
// TEXCOORD_0 in xy, _1 in zw
layout(std430, binding = UVS_BINDING) readonly buffer Uvs { vec4 uvs[]; };
layout(std430, binding = PREVIOUS_VERTICES_BINDING) readonly buffer PreviousVertices {
    DeformedVertex previousVertices[];
};
layout(std430, binding = NORMAL_DISTANCES_BINDING) readonly buffer NormalDistances {
    float normalDistance[];
};

uniform mat4 uModelView;       // mesh node space -> view
uniform mat3 uNormalMatrix;    // inverse transpose of uModelView's 3x3
uniform mat4 uProjection;
uniform int uHasNormalDistance;
uniform int uDistanceBase; // this primitive's first vertex in the character's d_N
uniform mat4 uModel, uPreviousModel; // mesh node space -> world, now and on the previous frame

out vec3 vViewPosition;
out vec3 vViewNormal;
out vec4 vViewTangent;
out vec4 vUv;
out float vNormalDistance;
out vec4 vClip, vPreviousClip; // unjittered, this frame and the previous one

void main() {
    DeformedVertex v = vertices[gl_VertexID];
    vec4 view = uModelView * vec4(v.position.xyz, 1.0);
    vViewPosition = view.xyz;
    vViewNormal = normalize(uNormalMatrix * v.normal.xyz);
    vViewTangent = vec4(normalize(mat3(uModelView) * v.tangent.xyz), v.tangent.w);
    vUv = uvs[gl_VertexID];
    // d_N is measured in world units, which the view (rigid) keeps.
    vNormalDistance = uHasNormalDistance != 0 ? normalDistance[uDistanceBase + gl_VertexID] : -1.0;
    vClip = vPreviousClip = vec4(0.0, 0.0, 0.0, 1.0);
    if (writesMotion()) {
        vClip = uMotionViewProjection * uModel * vec4(v.position.xyz, 1.0);
        vPreviousClip = uPreviousViewProjection * uPreviousModel *
                        vec4(previousVertices[gl_VertexID].position.xyz, 1.0);
    }
    gl_Position = uProjection * view;
}
