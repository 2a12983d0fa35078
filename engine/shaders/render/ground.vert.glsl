// A square ground plane at height uHeight, centred under the character.
uniform mat4 uViewProjection;
uniform vec3 uCenter;
uniform float uHalfSize;
uniform float uHeight;
out vec3 vWorldPosition;

void main() {
    const vec2 corners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
    vec2 c = corners[gl_VertexID] * uHalfSize;
    vWorldPosition = vec3(uCenter.x + c.x, uHeight, uCenter.z - c.y);
    gl_Position = uViewProjection * vec4(vWorldPosition, 1.0);
}
