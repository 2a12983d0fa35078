// The caustics atlas, one view's tile (refraction.caustic_resolve, drawn over the tile with
// render/fullscreen.vert.glsl): per texel, the photons' light read bilinearly from the cells
// around it (their splat bilinear too: a tent two cells wide), as a share of the light that
// reaches the receiver unblocked (RGB), and the distance of the nearest receiver its light meets
// (A: the opaque casters' depth atlas over the texel's shadow texels, or the ground square along
// its centre's ray; NO_GLASS where none), which common/shadows.glsl tells receivers by.
#include "common/lighting.glsl"
#include "refraction/caustics.glsl"

layout(binding = CAUSTIC_DEPTH_UNIT) uniform sampler2D uCausticDepth;
uniform int uView;
uniform mat4 uInverseViewProjection; // the view's
uniform int uPhotonBudget;

layout(location = 0) out vec4 outCaustic;

// World point of the view's texel centre `ndc` at depth `depth` (0 near, 1 far).
vec3 unproject(vec2 ndc, float depth) {
    vec4 p = uInverseViewProjection * vec4(ndc, depth * 2.0 - 1.0, 1.0);
    return p.xyz / p.w;
}

void main() {
    ShadowView view = shadowViews[uView];
    ivec2 corner = ivec2(round(view.tile.xy * vec2(uCausticSize)));
    int side = int(round(view.tile.z * float(uCausticSize.x)));
    ivec2 texel = ivec2(gl_FragCoord.xy), inTile = texel - corner;
    int cell, photons;
    causticGrid(uint(uPhotonBudget), cell, photons);
    int cells = (side + cell - 1) / cell;
    vec2 c = (vec2(inTile) + 0.5) / float(cell) - 0.5;
    ivec2 c0 = ivec2(floor(c));
    vec2 f = c - vec2(c0);
    vec3 light = vec3(0.0);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
            ivec2 at = clamp(c0 + ivec2(x, y), ivec2(0), ivec2(cells - 1));
            float w = (x == 0 ? 1.0 - f.x : f.x) * (y == 0 ? 1.0 - f.y : f.y);
            uint i = 3u * causticTexelIndex(corner + at * cell);
            light += w * vec3(causticSums[i], causticSums[i + 1u], causticSums[i + 2u]);
        }
    // The nearest receiver: the casters over the texel's shadow texels, the ground at its centre.
    float receiver = NO_GLASS;
    ivec2 shadowCorner = corner * CAUSTIC_SCALE;
    for (int y = 0; y < CAUSTIC_SCALE; ++y)
        for (int x = 0; x < CAUSTIC_SCALE; ++x) {
            ivec2 s = inTile * CAUSTIC_SCALE + ivec2(x, y);
            float depth = texelFetch(uCausticDepth, shadowCorner + s, 0).r;
            if (depth < 1.0) {
                vec2 ndc = (vec2(s) + 0.5) / view.texel.w * 2.0 - 1.0;
                receiver = min(receiver, shadowDistance(view, unproject(ndc, depth)));
            }
        }
    vec2 ndc = (vec2(inTile) + 0.5) / float(side) * 2.0 - 1.0;
    vec3 near = unproject(ndc, 0.0), dir = normalize(unproject(ndc, 1.0) - near);
    float ground = groundDistance(near, dir);
    if (ground > 0.0)
        receiver = min(receiver, shadowDistance(view, near + ground * dir));
    outCaustic = vec4(light / CAUSTIC_FIXED, receiver);
}
