// BVH refit, one tree level per dispatch from the leaves up: a leaf bounds its deformed
// triangles (and copies their corners in leaf order for the casts), an inner node the union of
// its children.
#include "refraction/bvh.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 5) readonly buffer Level { int levelNodes[]; };
uniform int uFirst;
uniform int uCount;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount))
        return;
    int n = levelNodes[uFirst + int(i)];
    BvhNode node = nodes[n];
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    if (node.left < 0) {
        for (int t = 0; t < node.count; ++t) {
            uint tri = triangleOrder[node.first + t];
            for (uint k = 0u; k < 3u; ++k) {
                vec3 p = vertices[indices[3u * tri + k]].position.xyz;
                leafCorners[3 * (node.first + t) + int(k)] = vec4(p, 0.0);
                lo = min(lo, p);
                hi = max(hi, p);
            }
        }
    } else {
        lo = min(bounds[2 * node.left].xyz, bounds[2 * node.right].xyz);
        hi = max(bounds[2 * node.left + 1].xyz, bounds[2 * node.right + 1].xyz);
    }
    bounds[2 * n] = vec4(lo, 0.0);
    bounds[2 * n + 1] = vec4(hi, 0.0);
}
