// A debug view of the frame's shadow atlases (RenderSettings::shadowMapView), the atlas fitted
// into the frame, black around it: the casters' depth (a texel's distance from its light between
// its view's near plane, white, and far plane, black), the glass's transmittance (what passes
// straight through, exp(-optical depth); a dark grey where no glass is), or the caustics a plugin
// focused (the share of the unblocked light, 1 a mid grey; a dark grey outside the tiles).
#include "common/lighting.glsl"

out vec4 outColor;
layout(binding = SOURCE_UNIT) uniform sampler2D uAtlas;
uniform int uMode; // RenderSettings::ShadowMapView: 1 depth, 2 glass, 3 caustics
uniform vec2 uFrameSize;

const vec3 kNone = vec3(0.05);

// The casters' depth at atlas uv `uv` (its raw value `depth`), 1 at the near plane to 0 at the
// far, along the ray of the view whose tile holds it.
float nearness(vec2 uv, float depth) {
    for (int v = 0; v < MAX_SHADOW_VIEWS; ++v) {
        ShadowView view = shadowViews[v];
        vec2 inTile = (uv - view.tile.xy) / view.tile.zw;
        if (view.tile.z <= 0.0 || any(lessThan(inTile, vec2(0.0))) ||
            any(greaterThan(inTile, vec2(1.0))))
            continue;
        mat4 inverseViewProjection = inverse(view.viewProjection);
        vec4 at = inverseViewProjection * vec4(inTile * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        vec4 far = inverseViewProjection * vec4(inTile * 2.0 - 1.0, 1.0, 1.0);
        return 1.0 - shadowDistance(view, at.xyz / at.w) / shadowDistance(view, far.xyz / far.w);
    }
    return 0.0;
}

void main() {
    vec2 size = vec2(textureSize(uAtlas, 0));
    float scale = min(uFrameSize.x / size.x, uFrameSize.y / size.y);
    vec2 uv = (gl_FragCoord.xy - 0.5 * (uFrameSize - size * scale)) / (size * scale);
    outColor = vec4(0.0, 0.0, 0.0, 1.0);
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
        return;
    vec4 texel = textureLod(uAtlas, uv, 0.0);
    if (uMode == 1)
        outColor.rgb = texel.r < 1.0 ? vec3(nearness(uv, texel.r)) : kNone;
    else if (uMode == 2)
        outColor.rgb = texel.a < NO_GLASS ? exp(-max(texel.rgb, vec3(0.0))) : kNone;
    else
        outColor.rgb = texel.a < NO_GLASS ? 0.5 * texel.rgb : kNone;
}
