// A shadow caster from one light's view: the deformed vertex (the deform pass's buffer, as every
// pass draws it) placed in the world and projected by the view's matrix.
#include "common/vertex.glsl"

layout(std430, binding = VERTICES_BINDING) readonly buffer Vertices { DeformedVertex vertices[]; };

uniform mat4 uModel; // mesh node space -> world
uniform mat4 uViewProjection;

void main() {
    gl_Position = uViewProjection * (uModel * vec4(vertices[gl_VertexID].position.xyz, 1.0));
}
