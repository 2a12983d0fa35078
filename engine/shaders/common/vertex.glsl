// Deformed vertex layout shared by the deform pass (writer) and every pass that draws (reader).
#ifndef COMMON_VERTEX_GLSL
#define COMMON_VERTEX_GLSL
struct DeformedVertex {
    vec4 position; // xyz in the mesh node's space, w = 1
    vec4 normal;   // xyz unit normal, w = 0
    vec4 tangent;  // xyz unit tangent, w = handedness
};
#endif
