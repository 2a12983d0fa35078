// HDR scene colour -> display: exposure, ACES filmic fit (Narkowicz), sRGB encoding.
in vec2 vUv;
out vec4 outColor;
layout(binding = SOURCE_UNIT) uniform sampler2D uScene;
uniform float uExposure;
uniform int uRaw; // 1: pass the HDR colour through (hdrOutput frames)

vec3 acesFilm(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 linearToSrgb(vec3 c) {
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    vec3 hdr = texelFetch(uScene, ivec2(gl_FragCoord.xy), 0).rgb;
    if (uRaw != 0) {
        outColor = vec4(hdr, 1.0);
        return;
    }
    hdr *= uExposure;
    outColor = vec4(linearToSrgb(acesFilm(max(hdr, vec3(0.0)))), 1.0);
}
