// d_N (ISR §3): for every deformed vertex, the exact distance along -N to the nearest other
// surface of the deformed mesh, by traversing the refitted BVH. Misses (open meshes) give -1.
#include "refraction/bvh.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 6) writeonly buffer Distance { float distances[]; };
uniform int uVertexCount;
uniform float uEpsilon; // self-intersection offset, in mesh units

// The distance at which the ray enters the box [lo, hi] before tMax, or -1 when it misses. The
// box is padded by the self-intersection offset: a ray along one of its faces (a sphere's -N
// from a pole, through the opposite pole) is inside it, whichever side of the face it lies on.
float enterBox(vec3 origin, vec3 inverseDir, vec3 lo, vec3 hi, float tMax) {
    vec3 t0 = (lo - uEpsilon - origin) * inverseDir, t1 = (hi + uEpsilon - origin) * inverseDir;
    vec3 tNear = min(t0, t1), tFar = max(t0, t1);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
    float exit = min(min(tFar.x, tFar.y), min(tFar.z, tMax));
    return enter <= exit ? enter : -1.0;
}

// Möller-Trumbore; returns t or -1. Barycentrics within 1e-4 of an edge hit: a ray through an
// edge or vertex (a sphere's -N through the opposite vertex) hits one of the triangles there,
// whatever the rounding of the deformed vertices and normals.
float hitTriangle(vec3 origin, vec3 dir, vec3 a, vec3 b, vec3 c) {
    vec3 e1 = b - a, e2 = c - a;
    vec3 p = cross(dir, e2);
    float det = dot(e1, p);
    if (abs(det) < 1e-20)
        return -1.0;
    float inv = 1.0 / det;
    vec3 s = origin - a;
    float u = dot(s, p) * inv;
    if (u < -1e-4 || u > 1.0 + 1e-4)
        return -1.0;
    vec3 q = cross(s, e1);
    float v = dot(dir, q) * inv;
    if (v < -1e-4 || u + v > 1.0 + 1e-4)
        return -1.0;
    return dot(e2, q) * inv;
}

void main() {
    uint vid = gl_GlobalInvocationID.x;
    if (vid >= uint(uVertexCount))
        return;
    vec3 origin = vertices[vid].position.xyz;
    vec3 dir = -normalize(vertices[vid].normal.xyz);
    vec3 inverseDir = 1.0 / (dir + vec3(equal(dir, vec3(0.0))) * 1e-30);
    float best = 3.0e38;
    // Nearer child first, so that the first hits shorten the ray; a node waiting on the stack
    // is dropped once a hit is nearer than where the ray enters it.
    int stack[64];
    float entered[64];
    int top = 0;
    if (enterBox(origin, inverseDir, bounds[0].xyz, bounds[1].xyz, best) >= 0.0) {
        stack[0] = 0;
        entered[0] = 0.0;
        top = 1;
    }
    while (top > 0) {
        BvhNode node = nodes[stack[--top]];
        if (node.left < 0) {
            for (int t = 0; t < node.count; ++t) {
                int corner = 3 * (node.first + t);
                float h = hitTriangle(origin, dir, leafCorners[corner].xyz,
                                      leafCorners[corner + 1].xyz, leafCorners[corner + 2].xyz);
                if (h > uEpsilon && h < best)
                    best = h;
            }
            while (top > 0 && entered[top - 1] > best)
                --top;
            continue;
        }
        float tLeft = enterBox(origin, inverseDir, bounds[2 * node.left].xyz,
                               bounds[2 * node.left + 1].xyz, best);
        float tRight = enterBox(origin, inverseDir, bounds[2 * node.right].xyz,
                                bounds[2 * node.right + 1].xyz, best);
        bool leftFirst = tLeft >= 0.0 && (tRight < 0.0 || tLeft <= tRight);
        int near = leftFirst ? node.left : node.right, far = leftFirst ? node.right : node.left;
        float tNear = leftFirst ? tLeft : tRight, tFar = leftFirst ? tRight : tLeft;
        if (tFar >= 0.0 && top < 63) {
            stack[top] = far;
            entered[top++] = tFar;
        }
        if (tNear >= 0.0 && top < 63) {
            stack[top] = near;
            entered[top++] = tNear;
        }
        while (top > 0 && entered[top - 1] > best)
            --top;
    }
    distances[vid] = best < 3.0e38 ? best : -1.0;
}
