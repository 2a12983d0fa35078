// The caustics atlas, one view's tile (refraction.caustic_resolve, drawn over the tile with
// render/fullscreen.vert.glsl): per texel, the photons' light read bilinearly from the cells
// around it (their splat bilinear too: a tent two cells wide), as a share of the light that
// reaches the receiver unblocked (RGB); A 0, the tile's mark (outside the tiles the atlas
// clears to NO_GLASS, where common/shadows.glsl takes the light straight).
#include "common/lighting.glsl"
#include "refraction/caustics.glsl"

uniform int uView;
uniform int uPhotonBudget;

layout(location = 0) out vec4 outCaustic;

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
    outCaustic = vec4(light / CAUSTIC_FIXED, 0.0);
}
