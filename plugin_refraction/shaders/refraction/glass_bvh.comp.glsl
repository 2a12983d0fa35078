// The BVH's build and refit on the GPU (bvh.glsl), one stage a dispatch (BVH_STAGE):
//   1 centroid bounds: the box of the triangles' centroids (ordered-int atomics)
//   2 Morton codes: 30 bits of each centroid within that box (cubic cells), the key of a
//     (key, triangle) pair (pairs padded to a power of two sort last); the leaves
//   3 sort: one step (uSortSize, uSortStride) of a bitonic sort of the pairs
//   4 hierarchy (Karras 2012, "Maximizing parallelism in the construction of BVHs"): each
//     internal node's range of leaves from the sorted keys' common prefixes, its split, its
//     children and their parent
//   5 refit: from every leaf up, each node's box once both children have theirs (the second to
//     arrive computes it), packed for the traversal (packedBoxes) in the frame the last refit
//     left; the leaves' corners copied in leaf order; the next frame from the root's box
//   6 cost: the surface-area cost of the tree, sum of each node's area over the root's (fixed
//     point, 1/256 a node), which tells when a refitted tree has degraded enough to rebuild
#include "refraction/bvh.glsl"
#include "refraction/ordered.glsl"

// The node records (Bvh::Node), for the tests' reading of the tree: the traversal reads the
// children from the boxes (bvh.glsl's BvhBox).
struct BvhNode {
    int left, right;      // child nodes; -1 for a leaf
    int first, count;     // leaf: range in the triangle order
};
layout(std430, binding = BVH_NODES_BINDING) coherent buffer BvhNodes { BvhNode nodes[]; };

layout(local_size_x = 64) in;
layout(std430, binding = BVH_BUILD_BINDING) coherent buffer BvhBuild {
    int centroidMin[3], centroidMax[3]; // floats as ordered ints
    uint cost;                          // stage 6, 1/256 of the root's area
};
// sorted with triangleOrder
layout(std430, binding = BVH_KEYS_BINDING) coherent buffer BvhKeys { uint keys[]; };
layout(std430, binding = BVH_PARENTS_BINDING) coherent buffer BvhParents { int parents[]; };
// stage 5, zeroed before
layout(std430, binding = BVH_VISITS_BINDING) coherent buffer BvhVisits { uint visits[]; };

uniform int uCount;     // threads: triangles n (stages 1, 4, 5), pairs (2, 3), GlassBvh's (6)
uniform int uTriangles; // n
uniform int uSortSize, uSortStride; // stage 3

vec3 corner(uint triangle, uint k) {
    vec3 p = vertices[indices[3u * triangle + k]].position.xyz;
    // An exploded pose (non-finite positions) still builds a tree: such corners sit at the origin.
    return any(isnan(p)) || any(isinf(p)) ? vec3(0.0) : p;
}

vec3 centreOf(uint triangle) {
    return (corner(triangle, 0u) + corner(triangle, 1u) + corner(triangle, 2u)) / 3.0;
}

// 10 bits of x spread to every third bit.
uint spreadBits(uint x) {
    x = (x | (x << 16)) & 0x030000FFu;
    x = (x | (x << 8)) & 0x0300F00Fu;
    x = (x | (x << 4)) & 0x030C30C3u;
    return (x | (x << 2)) & 0x09249249u;
}

// The length of the common prefix of sorted leaves i and j (ties broken by their positions:
// every key is unique), -1 outside the leaves.
int delta(int i, int j) {
    if (j < 0 || j >= uCount)
        return -1;
    uint a = keys[i], b = keys[j];
    return a != b ? 31 - findMSB(a ^ b) : 32 + 31 - findMSB(uint(i ^ j));
}

// A box as the traversal reads it (packedBoxes) in the frame at frameLo, cells `cell`: outward,
// and 0 or 65535 (no bound) where it leaves the frame.
uvec4 packBox(vec3 lo, vec3 hi, int children, vec3 frameLo, vec3 cell) {
    vec3 l = floor((lo - frameLo) / cell), h = ceil((hi - frameLo) / cell);
    l = mix(clamp(l, 0.0, 65535.0), vec3(0.0), isnan(l));
    h = mix(clamp(h, 0.0, 65535.0), vec3(65535.0), isnan(h));
    uvec3 a = uvec3(l), b = uvec3(h);
    return uvec4(a.x | a.y << 16, a.z | b.x << 16, b.y | b.z << 16, uint(children));
}

float area(vec3 lo, vec3 hi) {
    vec3 d = max(hi - lo, vec3(0.0));
    return d.x * d.y + d.y * d.z + d.z * d.x;
}

#if BVH_STAGE == 6
shared uint groupCost;

// Stage 6: the tree's cost, its nodes' areas relative to the root's summed.
void treeCost(int i) {
    // The 2n - 1 nodes shared among uCount threads, a work group's sums added in shared memory,
    // then to the counter at once: an atomic a node on the one counter cost more than the refit
    // itself on a CPU rasteriser.
    if (gl_LocalInvocationIndex == 0u)
        groupCost = 0u;
    barrier();
    float root = max(area(boxes[0].lo, boxes[0].hi), 1e-30);
    int nodes = 2 * uTriangles - 1, each = (nodes + uCount - 1) / uCount;
    uint sum = 0u;
    for (int node = i * each; node < min(i * each + each, nodes); ++node)
        sum += uint(round(clamp(area(boxes[node].lo, boxes[node].hi) / root, 0.0, 1.0) * 256.0));
    atomicAdd(groupCost, sum);
    barrier();
    if (gl_LocalInvocationIndex == 0u)
        atomicAdd(cost, groupCost);
}
#elif BVH_STAGE == 1
// Stage 1: the bounds of the triangles' centroids.
void centroidBounds(int i) {
    vec3 c = centreOf(uint(i));
    for (int a = 0; a < 3; ++a) {
        atomicMin(centroidMin[a], floatToOrdered(c[a]));
        atomicMax(centroidMax[a], floatToOrdered(c[a]));
    }
}
#elif BVH_STAGE == 2
// Stage 2: each triangle's Morton code (cubic cells over the centroids' bounds), its leaf.
void mortonKeys(int i) {
    // Every slot of the padded pairs; the real triangles' leaves too.
    uint key = 0xFFFFFFFFu;
    if (i < uTriangles) {
        vec3 lo = vec3(orderedToFloat(centroidMin[0]), orderedToFloat(centroidMin[1]),
                       orderedToFloat(centroidMin[2]));
        vec3 hi = vec3(orderedToFloat(centroidMax[0]), orderedToFloat(centroidMax[1]),
                       orderedToFloat(centroidMax[2]));
        // Cubic cells (each axis over the longest's extent): per-axis cells made a tall
        // character's boxes tall and thin, and its rays visit more of them.
        float extent = max(max(hi.x - lo.x, hi.y - lo.y), max(hi.z - lo.z, 1e-30));
        uvec3 q = uvec3(clamp((centreOf(uint(i)) - lo) / extent, 0.0, 1.0) * 1023.0);
        key = (spreadBits(q.x) << 2) | (spreadBits(q.y) << 1) | spreadBits(q.z);
        nodes[uTriangles - 1 + i] = BvhNode(-1, -1, i, 1);
    }
    keys[i] = key;
    triangleOrder[i] = uint(i);
}
#elif BVH_STAGE == 3
// Stage 3: one step of the bitonic sort of the keys with the triangles' order.
void sortStep(int i) {
    int j = i ^ uSortStride;
    if (j > i) {
        bool ascending = (i & uSortSize) == 0;
        uint ki = keys[i], kj = keys[j], vi = triangleOrder[i], vj = triangleOrder[j];
        bool greater = ki > kj || (ki == kj && vi > vj);
        if (greater == ascending) {
            keys[i] = kj;
            keys[j] = ki;
            triangleOrder[i] = vj;
            triangleOrder[j] = vi;
        }
    }
}
#elif BVH_STAGE == 4
// Stage 4: internal node i of Karras's hierarchy, its children and their parent.
void hierarchy(int i) {
    if (i == uCount - 1)
        return; // n - 1 internal nodes
    int d = delta(i, i + 1) > delta(i, i - 1) ? 1 : -1;
    int dMin = delta(i, i - d);
    int lMax = 2;
    while (delta(i, i + lMax * d) > dMin)
        lMax *= 2;
    int l = 0;
    for (int t = lMax / 2; t >= 1; t /= 2)
        if (delta(i, i + (l + t) * d) > dMin)
            l += t;
    int j = i + l * d;
    int dNode = delta(i, j);
    int s = 0, t = l;
    do {
        t = (t + 1) / 2;
        if (delta(i, i + (s + t) * d) > dNode)
            s += t;
    } while (t > 1);
    int gamma = i + s * d + min(d, 0);
    int leaves = uCount - 1;
    int left = min(i, j) == gamma ? leaves + gamma : gamma;
    int right = max(i, j) == gamma + 1 ? leaves + gamma + 1 : gamma + 1;
    nodes[i] = BvhNode(left, right, 0, 0);
    boxes[i].children = gamma << 2 | (left == leaves + gamma ? 2 : 0) |
                        (right == leaves + gamma + 1 ? 1 : 0);
    parents[left] = i;
    parents[right] = i;
    if (i == 0)
        parents[0] = -1;
}
#elif BVH_STAGE == 5
// Stage 5: leaf i's box and corners, then its ancestors' boxes, each by the last of its
// two subtrees to finish.
void refit(int i) {
    int node = uCount - 1 + i;
    uint triangle = triangleOrder[i];
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    for (uint k = 0u; k < 3u; ++k) {
        vec3 p = corner(triangle, k);
        leafCorners[3 * i + int(k)] = vec4(p, 0.0);
        lo = min(lo, p);
        hi = max(hi, p);
    }
    // The frame the boxes are packed in (the division rounds by a few thousandths of a cell,
    // which the traversal's pad, 1e-5 of the root's diagonal, covers many times over).
    vec3 frameLo, cell;
    bvhFrame(frameLo, cell);
    boxes[node].lo = lo;
    boxes[node].hi = hi;
    packedBoxes[node] = packBox(lo, hi, 0, frameLo, cell);
    memoryBarrierBuffer();
    int p = uCount > 1 ? parents[node] : -1;
    while (p >= 0) {
        if (atomicAdd(visits[p], 1u) == 0u)
            return; // the sibling's subtree is not done: its last thread goes on
        memoryBarrierBuffer();
        // The sibling from the parent's children word (stage 4's, as the traversal reads it).
        int children = boxes[p].children, gamma = children >> 2;
        int left = (children & 2) != 0 ? uCount - 1 + gamma : gamma;
        int right = (children & 1) != 0 ? uCount + gamma : gamma + 1;
        int sibling = left == node ? right : left;
        lo = min(lo, boxes[sibling].lo);
        hi = max(hi, boxes[sibling].hi);
        boxes[p].lo = lo;
        boxes[p].hi = hi;
        packedBoxes[p] = packBox(lo, hi, children, frameLo, cell);
        memoryBarrierBuffer();
        node = p;
        p = parents[p];
    }
    // This thread made the root's box: the next refit's frame.
    float grow = max(max(hi.x - lo.x, hi.y - lo.y), hi.z - lo.z) / 8.0;
    int frame = boxes.length();
    packedBoxes[frame + 2] = uvec4(floatBitsToUint(lo - grow), 0u);
    packedBoxes[frame + 3] = uvec4(floatBitsToUint(hi + grow), 0u);
}
#endif

void main() {
    int i = int(gl_GlobalInvocationID.x);
#if BVH_STAGE == 6
    treeCost(i); // every thread of the group: it meets barriers
#else
    if (i >= uCount)
        return;
#if BVH_STAGE == 1
    centroidBounds(i);
#elif BVH_STAGE == 2
    mortonKeys(i);
#elif BVH_STAGE == 3
    sortStep(i);
#elif BVH_STAGE == 4
    hierarchy(i);
#elif BVH_STAGE == 5
    refit(i);
#endif
#endif
}
