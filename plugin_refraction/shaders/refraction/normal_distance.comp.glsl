// d_N (ISR §3): for every vertex of the world mesh, the exact distance along -N to the nearest
// other glass surface, by traversing the refitted BVH (bvh.glsl), past any opaque part it holds.
// Misses (open meshes) give -1.
#include "refraction/bvh.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = NORMAL_DISTANCES_BINDING) writeonly buffer NormalDistances {
    float distances[];
};
uniform int uVertexCount;

void main() {
    uint vid = gl_GlobalInvocationID.x;
    if (vid >= uint(uVertexCount))
        return;
    // The self-intersection offset: 1e-4 of the glass's extent (the root's box).
    float epsilon = 1e-4 * length(boxes[0].hi - boxes[0].lo);
    float t;
    int leaf;
    vec2 uv;
    int steps = 0;
    // Opaque parts in the BVH (the caustics' receivers) are passed through: d_N is to glass.
    vec3 origin = vertices[vid].position.xyz, dir = -normalize(vertices[vid].normal.xyz);
    float along = 0.0;
    bool hit = false;
    for (int k = 0; k < 8; ++k) {
        hit = bvhNearest(origin, dir, epsilon, 3.0e38, t, leaf, uv, steps);
        if (!hit || (triangleTags[triangleOrder[leaf]] & kOpaqueTag) == 0u)
            break;
        along += t;
        origin += t * dir;
        hit = false;
    }
    distances[vid] = hit ? along + t : -1.0;
}
