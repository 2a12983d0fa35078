// d_N (ISR §3): for every deformed vertex, the exact distance along -N to the nearest other
// surface of the deformed mesh, by traversing the refitted BVH. Misses (open meshes) give -1.
#include "refraction/bvh.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 6) writeonly buffer Distance { float distances[]; };
uniform int uVertexCount;
uniform float uEpsilon; // self-intersection offset, in mesh units

bool hitBox(vec3 origin, vec3 inverseDir, vec3 lo, vec3 hi, float tMax) {
    vec3 t0 = (lo - origin) * inverseDir, t1 = (hi - origin) * inverseDir;
    vec3 tNear = min(t0, t1), tFar = max(t0, t1);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
    float exit = min(min(tFar.x, tFar.y), min(tFar.z, tMax));
    return enter <= exit;
}

// Möller-Trumbore; returns t or -1.
float hitTriangle(vec3 origin, vec3 dir, vec3 a, vec3 b, vec3 c) {
    vec3 e1 = b - a, e2 = c - a;
    vec3 p = cross(dir, e2);
    float det = dot(e1, p);
    if (abs(det) < 1e-20)
        return -1.0;
    float inv = 1.0 / det;
    vec3 s = origin - a;
    float u = dot(s, p) * inv;
    if (u < 0.0 || u > 1.0)
        return -1.0;
    vec3 q = cross(s, e1);
    float v = dot(dir, q) * inv;
    if (v < 0.0 || u + v > 1.0)
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
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        int n = stack[--top];
        if (!hitBox(origin, inverseDir, bounds[2 * n].xyz, bounds[2 * n + 1].xyz, best))
            continue;
        BvhNode node = nodes[n];
        if (node.left < 0) {
            for (int t = 0; t < node.count; ++t) {
                uint tri = triangleOrder[node.first + t];
                vec3 a = vertices[indices[3u * tri]].position.xyz;
                vec3 b = vertices[indices[3u * tri + 1u]].position.xyz;
                vec3 c = vertices[indices[3u * tri + 2u]].position.xyz;
                float h = hitTriangle(origin, dir, a, b, c);
                if (h > uEpsilon && h < best)
                    best = h;
            }
        } else if (top < 62) {
            stack[top++] = node.left;
            stack[top++] = node.right;
        }
    }
    distances[vid] = best < 3.0e38 ? best : -1.0;
}
