// Bounding-volume hierarchy over a primitive's triangles with static topology, refitted to the
// deformed vertices every frame (for d_N).
#ifndef REFRACTION_BVH_GLSL
#define REFRACTION_BVH_GLSL
#include "common/vertex.glsl"

struct BvhNode {
    int left, right;      // child nodes; -1 for a leaf
    int first, count;     // leaf: range in the triangle order
};

layout(std430, binding = 0) readonly buffer Deformed { DeformedVertex vertices[]; };
layout(std430, binding = 1) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 2) readonly buffer Nodes { BvhNode nodes[]; };
layout(std430, binding = 3) readonly buffer Order { uint triangleOrder[]; };
layout(std430, binding = 4) buffer Bounds { vec4 bounds[]; }; // [2 * node]: min, [2 * node + 1]: max
// The deformed corners of each triangle in leaf order (3 per triangle, written by the refit), so
// that a ray test reads them directly instead of through the order and the index buffer.
layout(std430, binding = 7) buffer LeafTriangles { vec4 leafCorners[]; };
#endif
