// The caustics' storage (CausticsPass.cpp, docs/materials.md "Caustics"). The emitters: a bit
// for each texel of the caustics atlas whose light meets glass, set by the glass shadow pass
// (glass_shadow.frag.glsl), and how many are set. The photon pass (caustic_photons.comp.glsl)
// spreads the frame's photon budget over them: a photon every `cell` texels each way, or
// `side` x `side` photons a texel (causticGrid), an invocation a cell of the atlas. The sums: the
// light the photons bring to each cell and how many photons brought it, four words (RGB and
// the count, CAUSTIC_FIXED units a 1: the light of one cell unblocked, one photon), on two grids:
// cells of `cell` x `cell` texels from their tile's corner, their sums at their corner texel,
// and after them cells CAUSTIC_COARSE times as wide (their light only, the nearest cell's). The resolve (caustic_resolve.frag.glsl)
// reads the fine cells where enough photons landed and the coarse ones where few did, so that a
// thin spread of light is a glow, not a speckle.
#ifndef REFRACTION_CAUSTICS_GLSL
#define REFRACTION_CAUSTICS_GLSL

uniform ivec2 uCausticSize; // the caustics atlas's texels: the shadow atlases' / CAUSTIC_SCALE

// After the bits, the list of the frame's photons (CausticsPass.cpp, caustic_photons.comp.glsl):
// each its cell of the grid and its stratum in the cell, packed (photonEntry), listed by the
// list pass so that the photon pass's lanes all trace (most cells of the atlas see no glass).
layout(std430, binding = CAUSTIC_EMITTERS_BINDING) buffer CausticEmitters {
    uint emitterCount;
    uint listGroups[3];   // the list pass's work groups (an invocation a cell of the grid)
    uint photonCount;
    uint photonGroups[3]; // the photon pass's work groups (64 photons each)
    uint emitterWords[];  // a bit a texel, row by row; then the photon list
};

uint photonListStart() {
    return (uint(uCausticSize.x) * uint(uCausticSize.y) + 31u) / 32u;
}
layout(std430, binding = CAUSTIC_SUMS_BINDING) buffer CausticSums { uint causticSums[]; };

// A shadow view's tile (ShadowView::tile, atlas uv) in the caustics atlas: its corner and side
// in texels.
ivec3 causticTile(vec4 tile) {
    return ivec3(round(tile.xy * vec2(uCausticSize)), round(tile.z * float(uCausticSize.x)));
}

uint causticTexelIndex(ivec2 texel) {
    return uint(texel.y) * uint(uCausticSize.x) + uint(texel.x);
}

bool isEmitter(ivec2 texel) {
    uint i = causticTexelIndex(texel);
    return (emitterWords[i / 32u] & (1u << (i % 32u))) != 0u;
}

// A photon of the list: its cell (13 bits each way: atlases up to 8192 texels a side) and its
// stratum in the cell (6 bits: up to 4 x 4).
uint photonEntry(ivec2 cell, int stratum) {
    return uint(cell.x) | uint(cell.y) << 13 | uint(stratum) << 26;
}

void photonOf(uint entry, out ivec2 cell, out int stratum) {
    cell = ivec2(entry & 0x1FFFu, (entry >> 13) & 0x1FFFu);
    stratum = int(entry >> 26);
}

// Photons a fine cell's estimate needs (over its bilinear footprint) to be read alone.
const float kCausticEnoughPhotons = 4.0;

// Grid `level`'s cell `at` (0 fine, 1 coarse; `at` in cells from the tile's corner `corner`, for
// fine cells of `cell` texels): its first word in the sums.
uint causticCellWord(ivec2 corner, ivec2 at, int cell, int level) {
    int size = level == 0 ? cell : cell * CAUSTIC_COARSE;
    uint base = level == 0 ? 0u : 4u * uint(uCausticSize.x) * uint(uCausticSize.y);
    return base + 4u * causticTexelIndex(corner + at * size);
}

// The cells of grid `level` around the point `at` of a tile (texels from its corner `corner`,
// its side `side`) and their bilinear weights: the cells' centres at (i + 0.5) cell sizes.
void causticCells(ivec2 corner, int side, vec2 at, int cell, int level, out uint words[4],
                  out float weights[4]) {
    int size = level == 0 ? cell : cell * CAUSTIC_COARSE;
    int cells = (side + size - 1) / size;
    vec2 c = at / float(size) - 0.5;
    ivec2 c0 = ivec2(floor(c));
    vec2 f = c - vec2(c0);
    for (int k = 0; k < 4; ++k) {
        ivec2 offset = ivec2(k & 1, k >> 1);
        words[k] = causticCellWord(corner, clamp(c0 + offset, ivec2(0), ivec2(cells - 1)), cell,
                                   level);
        weights[k] = (offset.x == 0 ? 1.0 - f.x : f.x) * (offset.y == 0 ? 1.0 - f.y : f.y);
    }
}

// The frame's photon grid for `budget` photons over the emitters: cells of `cell` texels a side
// with one photon each where the emitters outnumber the budget, else cells of one texel with
// side x side photons (at most 4 x 4).
void causticGrid(uint budget, out int cell, out int side) {
    float spacing = sqrt(float(emitterCount) / float(max(budget, 1u)));
    cell = max(int(ceil(spacing - 1e-4)), 1);
    side = cell > 1 ? 1 : clamp(int(floor(1.0 / max(spacing, 1e-3))), 1, 4);
}

#endif
