// The camera's projection and the viewport, as every screen-space search uses them.
#ifndef REFRACTION_VIEW_GLSL
#define REFRACTION_VIEW_GLSL
uniform mat4 uProjection;
uniform vec2 uViewportSize;

// Texture coordinate of a view-space point.
vec2 projectToUv(vec3 p) {
    vec4 clip = uProjection * vec4(p, 1.0);
    return clip.xy / clip.w * 0.5 + 0.5;
}
#endif
