// Subdivision: one float per refined vertex to one per drawn vertex (corner), for values that
// follow the refinement (GpuDeformer::refineScalar).
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Corners { uvec2 corners[]; }; // vertex, value
layout(std430, binding = 1) readonly buffer Refined { float refined[]; };
layout(std430, binding = 2) writeonly buffer Drawn { float drawn[]; };

uniform int uCornerCount;

void main() {
    uint o = gl_GlobalInvocationID.x;
    if (o < uint(uCornerCount))
        drawn[o] = refined[corners[o].x];
}
