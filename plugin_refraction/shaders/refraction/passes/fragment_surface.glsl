// A glass fragment's material as the captures read it (layer_capture.frag.glsl, and the pair's
// pair_surface.frag.glsl): its texels, its normal after the normal map, and with textured glass
// in the frame (GLASS_TEXTURES) its surface, the material's factors times its textures.
#ifndef REFRACTION_FRAGMENT_SURFACE_GLSL
#define REFRACTION_FRAGMENT_SURFACE_GLSL
#include "common/material_uv.glsl"
#include "common/normal_map.glsl"
#include "refraction/passes/glass_inputs.glsl"
#include "refraction/model/glass_materials.glsl"

#ifndef GLASS_TEXTURES
#define GLASS_TEXTURES 0
#endif

// The trace reads glass textures at their base level wherever it meets them, as the reference
// does; the capture does so for the trace with several samples (TEXTURES_BASE_LEVEL: their
// entries), where the walk's and the one-sample trace's read them filtered (a pixel's texels
// averaged, closer to the reference's many rays than one texel).
#ifndef TEXTURES_BASE_LEVEL
#define TEXTURES_BASE_LEVEL 0
#endif
vec4 captureTexel(int slot) {
#ifdef SKIP_TEXTURES // glass-bench --skip textures: no texel read (a flat normal)
    return vec4(0.5, 0.5, 1.0, 1.0);
#elif TEXTURES_BASE_LEVEL
    return textureLod(uTexture[slot], slotUv(vUv, slot), 0.0);
#else
    return readTexture(slot, vUv);
#endif
}

uniform float uNormalScale;

// GLASS_NORMAL_MAPS: some glass of the frame has a normal map (the plugin's variants; on where
// not given).
#ifndef GLASS_NORMAL_MAPS
#define GLASS_NORMAL_MAPS 1
#endif

// The fragment's outward view normal (a back face's points away from the camera) after its
// normal map.
vec3 fragmentNormal() {
    vec3 n = normalize(vViewNormal);
#if GLASS_NORMAL_MAPS
    if (hasTexture(SLOT_NORMAL))
        n = perturbNormal(n, vViewTangent, captureTexel(SLOT_NORMAL).xyz, uNormalScale);
#endif
    return n;
}

#if GLASS_TEXTURES
// The glass's surface at the fragment (optics.glsl's GlassSurface): its optics' factors times the
// material's textures, as the trace and the reference read them at a hit.
GlassSurface fragmentSurface(uint id) {
    GlassMaterial m = glassMaterials[id];
    GlassSurface s = materialSurface(m);
#if GLASS_BASE_COLOR_TEXTURES
    if (hasTexture(SLOT_BASE_COLOR))
        s.baseColor *= captureTexel(SLOT_BASE_COLOR).rgb; // sRGB: decoded to linear
#endif
#if GLASS_TRANSMISSION_TEXTURES
    if (m.authored == 0u)
        return s;
    if (hasTexture(SLOT_TRANSMISSION))
        s.transmission *= captureTexel(SLOT_TRANSMISSION).r;
    if (hasTexture(SLOT_METALLIC_ROUGHNESS)) {
        vec4 mr = captureTexel(SLOT_METALLIC_ROUGHNESS);
        s.roughness *= mr.g;
        s.metallic *= mr.b;
    }
#endif
    return s;
}
#endif

#endif
