// GPU deformation: morph (base + sum of weighted deltas), then skin (blend of skin matrices by
// up to 8 influences); normals by the inverse transpose of the blended matrix. One thread per
// vertex; writes the one deformed vertex buffer every later pass reads.
#include "common/vertex.glsl"

layout(local_size_x = 64) in;

struct Influence {
    uvec4 joints0;
    uvec4 joints1;
    vec4 weights0;
    vec4 weights1;
};

layout(std430, binding = REST_BINDING) readonly buffer Rest { DeformedVertex rest[]; };
layout(std430, binding = INFLUENCES_BINDING) readonly buffer Influences { Influence influences[]; };
// [target][vertex][3]
layout(std430, binding = MORPH_DELTAS_BINDING) readonly buffer MorphDeltas { vec4 deltas[]; };
layout(std430, binding = MORPH_WEIGHTS_BINDING) readonly buffer MorphWeights { float weights[]; };
layout(std430, binding = SKIN_MATRICES_BINDING) readonly buffer SkinMatrices { mat4 skin[]; };
layout(std430, binding = VERTICES_BINDING) writeonly buffer Vertices { DeformedVertex deformed[]; };

uniform int uVertexCount;
uniform int uTargetCount;
uniform int uSkinned; // 0: rest space is the mesh node's space
uniform int uSkinBase;   // this mesh node's first matrix in SkinMatrices (every character's)
uniform int uWeightBase; // its first weight in MorphWeights

void main() {
    uint v = gl_GlobalInvocationID.x;
    if (v >= uint(uVertexCount))
        return;
    vec3 position = rest[v].position.xyz;
    vec3 normal = rest[v].normal.xyz;
    vec3 tangent = rest[v].tangent.xyz;
    for (uint t = 0u; t < uint(uTargetCount); ++t) {
        float w = weights[uint(uWeightBase) + t];
        if (w == 0.0)
            continue;
        uint base = (t * uint(uVertexCount) + v) * 3u;
        position += w * deltas[base].xyz;
        normal += w * deltas[base + 1u].xyz;
        tangent += w * deltas[base + 2u].xyz;
    }
    mat4 blend = mat4(1.0);
    if (uSkinned != 0) {
        Influence inf = influences[v];
        uvec4 j0 = inf.joints0 + uint(uSkinBase);
        blend = inf.weights0.x * skin[j0.x] + inf.weights0.y * skin[j0.y] +
                inf.weights0.z * skin[j0.z] + inf.weights0.w * skin[j0.w];
        // Most files give four influences: the second four (zero weights) are skipped, which
        // halves the matrix reads where no vertex of a group has more.
        if (inf.weights1 != vec4(0.0)) {
            uvec4 j1 = inf.joints1 + uint(uSkinBase);
            blend += inf.weights1.x * skin[j1.x] + inf.weights1.y * skin[j1.y] +
                     inf.weights1.z * skin[j1.z] + inf.weights1.w * skin[j1.w];
        }
    }
    mat3 linear = mat3(blend);
    // The inverse transpose up to a positive factor: the cofactor matrix, signed by the
    // determinant (normals are normalised below), without a division or a full inverse.
    mat3 cofactor = mat3(cross(linear[1], linear[2]), cross(linear[2], linear[0]),
                         cross(linear[0], linear[1]));
    vec3 n = (dot(linear[0], cofactor[0]) < 0.0 ? -1.0 : 1.0) * (cofactor * normal);
    vec3 t3 = linear * tangent;
    deformed[v].position = vec4((blend * vec4(position, 1.0)).xyz, 1.0);
    deformed[v].normal = vec4(length(n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0), 0.0);
    deformed[v].tangent = vec4(length(t3) > 0.0 ? normalize(t3) : vec3(1.0, 0.0, 0.0), rest[v].tangent.w);
}
