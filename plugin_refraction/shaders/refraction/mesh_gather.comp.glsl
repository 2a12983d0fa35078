// The glass BVH's world mesh (GlassBvh::gather): copies one part's deformed vertices as drawn
// into it at uBase, in world space (each part's mesh node has its own matrix), so that one BVH
// over every part answers every ray.
#include "common/vertex.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = VERTICES_BINDING) readonly buffer Vertices { DeformedVertex part[]; };
layout(std430, binding = WORLD_MESH_BINDING) writeonly buffer WorldMesh { DeformedVertex world[]; };

uniform mat4 uWorld;        // mesh node -> world
uniform mat3 uNormalMatrix; // inverse transpose of uWorld's 3x3
uniform int uBase;
uniform int uVertexCount;

void main() {
    uint v = gl_GlobalInvocationID.x;
    if (v >= uint(uVertexCount))
        return;
    DeformedVertex d = part[v];
    d.position = vec4((uWorld * vec4(d.position.xyz, 1.0)).xyz, 1.0);
    d.normal = vec4(normalize(uNormalMatrix * d.normal.xyz), 0.0);
    vec3 tangent = mat3(uWorld) * d.tangent.xyz; // none (zero) where no normal map needs one
    d.tangent.xyz = dot(tangent, tangent) > 0.0 ? normalize(tangent) : tangent;
    world[uint(uBase) + v] = d;
}
