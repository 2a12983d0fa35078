// The BVH over the frame's deformed glass (GlassBvh.h): the world mesh of every glass part as drawn
// (and for the tracing methods every opaque one), its static triangles, and a linear BVH over them
// built on the GPU (glass_bvh.comp.glsl: Morton codes of the triangles' centroids, sorted; Karras
// 2012's hierarchy) and refitted to the deformed vertices every frame. Internal nodes 0..n-2 (the
// root is node 0), leaf k (one triangle, the k-th in Morton order) is node n-1+k; with one triangle
// the root is that leaf.
#ifndef REFRACTION_BVH_GLSL
#define REFRACTION_BVH_GLSL
#include "common/vertex.glsl"

layout(std430, binding = WORLD_MESH_BINDING) readonly buffer WorldMesh {
    DeformedVertex vertices[];
};
layout(std430, binding = WORLD_INDICES_BINDING) readonly buffer WorldIndices { uint indices[]; };
layout(std430, binding = BVH_ORDER_BINDING) coherent buffer BvhOrder { uint triangleOrder[]; };
// Each node's box and, for an inner node, its children as the traversal reads them with the box
// (bvhVisit): Karras's children of an inner node are gamma and gamma + 1, each an inner node
// or a leaf, so `children` is gamma << 2 | the left one's a leaf << 1 | the right one's a leaf.
struct BvhBox {
    vec3 lo;
    int children;
    vec3 hi;
    int spare;
};
layout(std430, binding = BVH_BOXES_BINDING) coherent buffer BvhBoxes { BvhBox boxes[]; };
// The deformed corners of each triangle in leaf order (3 per triangle, written by the refit), so
// that a ray test reads them directly instead of through the order and the index buffer.
layout(std430, binding = BVH_LEAF_CORNERS_BINDING) buffer BvhLeafCorners { vec4 leafCorners[]; };
// Each triangle's tag (GlassBvh::setTags), in the original order: its glass id
// (glass_materials.glsl), or kOpaqueTag with an opaque part's material factors.
layout(std430, binding = BVH_TAGS_BINDING) readonly buffer BvhTags { uint triangleTags[]; };
const uint kOpaqueTag = OPAQUE_TAG, kOpaqueTextured = OPAQUE_TEXTURED_TAG;
// The traversal's copy of each node's box, packed by the refit as it computes the box
// (glass_bvh.comp.glsl's stage 5): its corners in cells of the frame (bvhFrame), 16 bits an
// axis, rounded outward, and the children word: lo.x | lo.y << 16, lo.z | hi.x << 16,
// hi.y | hi.z << 16, children. A visit reads one vector of four words a child instead of two
// (seven words): on a CPU rasteriser the loads were most of a visit's cost. After the 2n - 1
// boxes, the frame they are packed in (its lo, then hi, as float bits), then the next update's
// (the root's box this update, grown by an eighth of its longest side each way: GlassBvh::refit
// copies it over the frame before the next refit). A corner outside the frame packs as 0 or
// 65535, which stand for no bound that way: a box is never smaller than its node's.
layout(std430, binding = BVH_PACKED_BOXES_BINDING) buffer BvhPackedBoxes { uvec4 packedBoxes[]; };

// The frame the boxes are packed in, and its cell: the frame in 65535 steps an axis (an axis
// along which it is flat takes a millionth of its longest's steps, so that no cell is empty).
// A frame that is not finite (an exploded pose's) is taken as cells of 1 from the origin.
void bvhFrame(out vec3 lo, out vec3 cell) {
    lo = uintBitsToFloat(packedBoxes[boxes.length()].xyz);
    vec3 extent = uintBitsToFloat(packedBoxes[boxes.length() + 1].xyz) - lo;
    float longest = max(max(extent.x, extent.y), extent.z);
    cell = max(extent, vec3(1e-6 * longest + 1e-30)) / 65535.0;
    if (any(isnan(lo)) || any(isinf(lo)) || any(isnan(cell)) || any(isinf(cell))) {
        lo = vec3(0.0);
        cell = vec3(1.0);
    }
}

// Where the ray enters the box [lo, hi] padded by `pad` before tMax, or -1 when it misses (a ray
// along one of its faces, a sphere's -N from a pole through the opposite pole, is inside it,
// whichever side of the face it lies on).
float bvhEnterBox(vec3 origin, vec3 inverseDir, vec3 lo, vec3 hi, vec3 pad, float tMax) {
    vec3 t0 = (lo - pad - origin) * inverseDir, t1 = (hi + pad - origin) * inverseDir;
    vec3 tNear = min(t0, t1), tFar = max(t0, t1);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
    float exit = min(min(tFar.x, tFar.y), min(tFar.z, tMax));
    return enter <= exit ? enter : -1.0;
}

// Möller-Trumbore: t, or -1, with the barycentrics of b and c. Barycentrics within 1e-4 of an
// edge hit: a ray through an edge or vertex hits one of the triangles there, whatever the
// rounding of the deformed vertices.
float bvhHitTriangle(vec3 origin, vec3 dir, vec3 a, vec3 b, vec3 c, out vec2 uv) {
    vec3 e1 = b - a, e2 = c - a;
    vec3 p = cross(dir, e2);
    float det = dot(e1, p);
    uv = vec2(0.0);
    if (abs(det) < 1e-20)
        return -1.0;
    float inv = 1.0 / det;
    vec3 s = origin - a;
    uv.x = dot(s, p) * inv;
    if (uv.x < -1e-4 || uv.x > 1.0 + 1e-4)
        return -1.0;
    vec3 q = cross(s, e1);
    uv.y = dot(dir, q) * inv;
    if (uv.y < -1e-4 || uv.x + uv.y > 1.0 + 1e-4)
        return -1.0;
    return dot(e2, q) * inv;
}

// The first leaf's node, n - 1 of 2n - 1 nodes (node 0, the root, when it is the only one).
int bvhFirstLeaf() {
    return (boxes.length() - 1) / 2;
}

// A node as the traversal's stack holds it: an inner node by its children (BvhBox.children),
// leaf k as -(k + 1), so that a visit reads no node record.
int bvhVisit(int node, int children, int firstLeaf) {
    return node >= firstLeaf ? firstLeaf - node - 1 : children;
}

// Node i's packed box (packedBoxes) in cells, unbounded where it lies outside the frame, and its
// children word.
void bvhPackedBox(int i, out vec3 lo, out vec3 hi, out int children) {
    uvec4 q = packedBoxes[i];
    uvec3 l = uvec3(q.x, q.x >> 16, q.y) & 0xFFFFu, h = uvec3(q.y >> 16, q.z, q.z >> 16) & 0xFFFFu;
    lo = mix(vec3(l), vec3(-3.0e38), equal(l, uvec3(0u)));
    hi = mix(vec3(h), vec3(3.0e38), equal(h, uvec3(0xFFFFu)));
    children = int(q.w);
}

// The nearest triangle along origin + t dir with epsilon < t < tMax: true with t, the hit leaf
// (its position in Morton order) and the barycentrics; `steps` counts the nodes visited. Nearer
// child first, so that the first hits shorten the ray; a node waiting on the stack is dropped
// once a hit is nearer than where the ray enters it. The boxes are tested in the packed boxes'
// cells, where the ray is taken once (t is the same along it). One loop iteration a node (a
// leaf holds one triangle): Mesa's llvmpipe ends every loop of a shader invocation after 65535
// iterations in all, so the traversal spends none on inner loops.
bool bvhNearest(vec3 origin, vec3 dir, float epsilon, float tMax, out float t, out int leaf,
                out vec2 uv, inout int steps) {
    vec3 inverseDir = 1.0 / (dir + vec3(equal(dir, vec3(0.0))) * 1e-30);
    t = tMax;
    leaf = -1;
    uv = vec2(0.0);
    int firstLeaf = bvhFirstLeaf();
    int stack[64];
    float entered[64];
    int top = 0;
    BvhBox root = boxes[0];
    vec3 frameLo, cell;
    bvhFrame(frameLo, cell);
    vec3 originCells = (origin - frameLo) / cell, inverseCells = inverseDir * cell;
    vec3 padCells = epsilon / cell;
    if (bvhEnterBox(origin, inverseDir, root.lo, root.hi, vec3(epsilon), t) >= 0.0) {
        stack[0] = bvhVisit(0, root.children, firstLeaf);
        entered[0] = 0.0;
        top = 1;
    }
    while (top > 0) {
        --top;
        if (entered[top] > t)
            continue; // a nearer hit was found since it was pushed
        ++steps;
        int visit = stack[top];
        if (visit < 0) {
            int k = -visit - 1;
            vec2 b;
            float h = bvhHitTriangle(origin, dir, leafCorners[3 * k].xyz,
                                     leafCorners[3 * k + 1].xyz, leafCorners[3 * k + 2].xyz, b);
            if (h > epsilon && h < t) {
                t = h;
                leaf = k;
                uv = b;
            }
            continue;
        }
        int gamma = visit >> 2;
        int left = (visit & 2) != 0 ? firstLeaf + gamma : gamma;
        int right = (visit & 1) != 0 ? firstLeaf + gamma + 1 : gamma + 1;
        vec3 lLo, lHi, rLo, rHi;
        int lChildren, rChildren;
        bvhPackedBox(left, lLo, lHi, lChildren);
        bvhPackedBox(right, rLo, rHi, rChildren);
        float tLeft = bvhEnterBox(originCells, inverseCells, lLo, lHi, padCells, t);
        float tRight = bvhEnterBox(originCells, inverseCells, rLo, rHi, padCells, t);
        bool leftFirst = tLeft >= 0.0 && (tRight < 0.0 || tLeft <= tRight);
        int leftVisit = bvhVisit(left, lChildren, firstLeaf);
        int rightVisit = bvhVisit(right, rChildren, firstLeaf);
        int near = leftFirst ? leftVisit : rightVisit, far = leftFirst ? rightVisit : leftVisit;
        float tNear = leftFirst ? tLeft : tRight, tFar = leftFirst ? tRight : tLeft;
        if (tFar >= 0.0 && top < 63) {
            stack[top] = far;
            entered[top++] = tFar;
        }
        if (tNear >= 0.0 && top < 63) {
            stack[top] = near;
            entered[top++] = tNear;
        }
    }
    return leaf >= 0;
}
#endif
