// The layered path's one geometry pass: every glass fragment, front- or back-facing, appends
// itself to its pixel's fixed array (layers.glsl): depth, outward normal after normal mapping,
// glass id, facing, d_N. Glass behind the opaque scene is kept too (a glass head's far side
// behind its opaque eyes, which rays inside the head still cross); the shading pass skips pixels
// whose nearest glass is hidden. Fragments past K only count; every fragment also bids for the
// pixel's overflow fallback (nearest front, farthest back). The depth attachment (depth test
// ALWAYS) is the shading pass's mask: below 1 where any glass was kept. With textured glass in
// the frame (GLASS_TEXTURES), each kept fragment's surface too.
#include "common/material_uv.glsl"
#include "common/normal_map.glsl"
#include "refraction/glass_inputs.glsl"
#include "refraction/view.glsl"
#include "refraction/layers.glsl"

uniform int uGlassId;
uniform float uNormalScale;

// The trace reads glass textures at their base level wherever it meets them, as the reference
// does; the capture does so for the trace with several samples (TEXTURES_BASE_LEVEL: their
// entries), where the walk's and the one-sample trace's read them filtered (a pixel's texels
// averaged, closer to the reference's many rays than one texel).
#ifndef TEXTURES_BASE_LEVEL
#define TEXTURES_BASE_LEVEL 0
#endif
vec4 captureTexel(int slot) {
#if TEXTURES_BASE_LEVEL
    return textureLod(uTexture[slot], slotUv(vUv, slot), 0.0);
#else
    return readTexture(slot, vUv);
#endif
}

#if GLASS_TEXTURES
// The glass's surface at the fragment (optics.glsl's GlassSurface): its optics' factors times the
// material's textures, as the trace and the reference read them at a hit.
GlassSurface fragmentSurface(uint id) {
    GlassMaterial m = glassMaterials[id];
    GlassSurface s = materialSurface(m);
    if (hasTexture(SLOT_BASE_COLOR))
        s.baseColor *= captureTexel(SLOT_BASE_COLOR).rgb; // sRGB: decoded to linear
    if (m.authored == 0u)
        return s;
    if (hasTexture(SLOT_TRANSMISSION))
        s.transmission *= captureTexel(SLOT_TRANSMISSION).r;
    if (hasTexture(SLOT_METALLIC_ROUGHNESS)) {
        vec4 mr = captureTexel(SLOT_METALLIC_ROUGHNESS);
        s.roughness *= mr.g;
        s.metallic *= mr.b;
    }
    return s;
}
#endif

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint pixel = pixelIndex(p);
    float z = -vViewPosition.z;
    vec3 n = normalize(vViewNormal);
    if (hasTexture(SLOT_NORMAL))
        n = perturbNormal(n, vViewTangent, captureTexel(SLOT_NORMAL).xyz, uNormalScale);
    uint id = uint(uGlassId);
    uint d = vNormalDistance >= 0.0 ? 1u + uint(round(clamp(vNormalDistance / z, 0.0, 1.0) * 65534.0)) : 0u;
    uint slot = atomicAdd(layerHeads[pixel], 1u);
    if (slot < uint(kLayerCapacity)) {
        layerDepth4[pixel * uint(kDepthGroups) + slot / 4u][slot % 4u] = z;
        layerAttr[pixel * uint(kLayerCapacity) + slot] = uvec2(packOctNormal(n), id | (gl_FrontFacing ? kLayerFront : 0u) | (d << 16));
#if GLASS_TEXTURES
        layerSurface[pixel * uint(kLayerCapacity) + slot] = packSurface(fragmentSurface(id));
#endif
    }
    if (gl_FrontFacing)
        atomicMin(layerHeads[uint(uPixelCount) + pixel], fallbackKey(z, n, id));
    else
        atomicMax(layerHeads[2u * uint(uPixelCount) + pixel], fallbackKey(z, n, id));
}
