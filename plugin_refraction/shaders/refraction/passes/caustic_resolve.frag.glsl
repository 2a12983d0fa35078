// The caustics atlas, one view's tile (refraction.caustic_resolve, drawn over the tile with
// render/fullscreen.vert.glsl): per texel, the photons' light read bilinearly from the cells
// around it (their splat bilinear too: a tent two cells wide), the fine cells' where enough
// photons landed, the coarse cells' where few did, as a share of the light that reaches the
// receiver unblocked (RGB); A 0, the tile's mark (outside the tiles the atlas
// clears to NO_GLASS, where common/shadows.glsl takes the light straight).
#include "common/lighting.glsl"
#include "refraction/passes/caustics.glsl"

uniform int uView;
uniform int uPhotonBudget;

layout(location = 0) out vec4 outCaustic;

void main() {
    ivec3 tile = causticTile(shadowViews[uView].tile);
    ivec2 corner = tile.xy, inTile = ivec2(gl_FragCoord.xy) - corner;
    int side = tile.z;
    int cell, photons;
    causticGrid(uint(uPhotonBudget), cell, photons);
    // Each grid's estimate here (RGB) and the photons in its footprint (A), a fine cell's area
    // the unit of both: the fine one where enough photons landed, else toward the coarse one.
    vec4 estimates[2];
    for (int level = 0; level < 2; ++level) {
        uint words[4];
        float weights[4];
        causticCells(corner, side, vec2(inTile) + 0.5, cell, level, words, weights);
        estimates[level] = vec4(0.0);
        for (int k = 0; k < 4; ++k)
            estimates[level] += weights[k] * vec4(causticSums[words[k]], causticSums[words[k] + 1u],
                                                  causticSums[words[k] + 2u],
                                                  causticSums[words[k] + 3u]);
    }
    estimates[1] /= float(CAUSTIC_COARSE * CAUSTIC_COARSE);
    float fine = clamp(estimates[0].a / (kCausticEnoughPhotons * CAUSTIC_FIXED), 0.0, 1.0);
    vec3 light = mix(estimates[1].rgb, estimates[0].rgb, fine);
    outCaustic = vec4(light / CAUSTIC_FIXED, 0.0);
}
