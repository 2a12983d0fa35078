// Subdivision, last step: one thread per output vertex of the refined mesh. Its refined vertex
// gives the limit position and the normal (du x dv of the limit surface); its face-varying value
// gives the tangent (the cage's deformed tangents refined, made orthogonal to the normal).
// Writes the DeformedVertex layout every later pass reads.
#include "common/vertex.glsl"

layout(local_size_x = 64) in;

// vertex, value
layout(std430, binding = CORNERS_BINDING) readonly buffer Corners { uvec2 corners[]; };
layout(std430, binding = LIMIT_BINDING) readonly buffer Limit { float limitPosition[]; };
layout(std430, binding = LIMIT_DU_BINDING) readonly buffer LimitDu { float du[]; };
layout(std430, binding = LIMIT_DV_BINDING) readonly buffer LimitDv { float dv[]; };
layout(std430, binding = REFINED_TANGENTS_BINDING) readonly buffer RefinedTangents {
    vec4 tangents[];
};
layout(std430, binding = VERTICES_BINDING) writeonly buffer Vertices { DeformedVertex deformed[]; };

uniform int uCornerCount;
uniform int uFlipNormals; // 1: du x dv points inside

vec3 at3(uint i, int which) {
    uint b = 3u * i;
    if (which == 0)
        return vec3(limitPosition[b], limitPosition[b + 1u], limitPosition[b + 2u]);
    if (which == 1)
        return vec3(du[b], du[b + 1u], du[b + 2u]);
    return vec3(dv[b], dv[b + 1u], dv[b + 2u]);
}

void main() {
    uint o = gl_GlobalInvocationID.x;
    if (o >= uint(uCornerCount))
        return;
    uvec2 c = corners[o];
    vec3 u = at3(c.x, 1), v = at3(c.x, 2);
    vec3 n = uFlipNormals != 0 ? cross(v, u) : cross(u, v);
    n = dot(n, n) > 1e-30 ? normalize(n) : vec3(0.0, 0.0, 1.0);
    vec4 t = tangents[c.y];
    vec3 tangent = t.xyz - n * dot(n, t.xyz);
    if (dot(tangent, tangent) < 1e-20)
        tangent = abs(n.x) < 0.9 ? cross(n, vec3(1.0, 0.0, 0.0)) : cross(n, vec3(0.0, 1.0, 0.0));
    deformed[o].position = vec4(at3(c.x, 0), 1.0);
    deformed[o].normal = vec4(n, 0.0);
    deformed[o].tangent = vec4(normalize(tangent), t.w < 0.0 ? -1.0 : 1.0);
}
