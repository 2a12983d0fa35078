// Flat normals after deformation, for primitives the file gave no NORMAL: one thread per
// triangle; the primitive is unwelded, so each vertex belongs to exactly one triangle.
#include "common/vertex.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = VERTICES_BINDING) buffer Vertices { DeformedVertex deformed[]; };
layout(std430, binding = INDICES_BINDING) readonly buffer Indices { uint indices[]; };

uniform int uTriangleCount;

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= uint(uTriangleCount))
        return;
    uint i0 = indices[3u * t], i1 = indices[3u * t + 1u], i2 = indices[3u * t + 2u];
    vec3 a = deformed[i0].position.xyz, b = deformed[i1].position.xyz, c = deformed[i2].position.xyz;
    vec3 n = cross(b - a, c - a);
    n = length(n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
    deformed[i0].normal = vec4(n, 0.0);
    deformed[i1].normal = vec4(n, 0.0);
    deformed[i2].normal = vec4(n, 0.0);
}
