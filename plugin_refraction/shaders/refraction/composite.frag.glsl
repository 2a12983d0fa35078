// Glass over the scene: where the front-face pass wrote glass (alpha 1) its colour, elsewhere
// the scene's.
in vec2 vUv;
out vec4 outColor;
uniform sampler2D uScene;
uniform sampler2D uGlass;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec4 glass = texelFetch(uGlass, texel, 0);
    outColor = glass.a > 0.5 ? vec4(glass.rgb, 1.0) : texelFetch(uScene, texel, 0);
}
