// The optics of the frame's glass, one entry per glass id (a character's material with its
// overrides: GlassMaterialGpu in GpuState.h, filled by assignGlassIds), read by every shading
// pass through the id its glass carries.
#ifndef REFRACTION_GLASS_MATERIALS_GLSL
#define REFRACTION_GLASS_MATERIALS_GLSL

struct GlassMaterial {
    vec4 ior;        // per channel (dispersion), w: transmission
    vec4 sigma;      // Beer-Lambert absorption per world unit, w: roughness
    vec4 baseColor;  // w: metallic
    vec4 emissive;   // w: the solid (character) it belongs to
    vec4 specular;   // KHR_materials_specular: rgb its colour, w its weight (all 1 without it)
    vec4 layers;     // x: clearcoat, y: its roughness, z: iridescence, w: the film's index
    vec4 sheen;      // rgb: sheen colour, w: its roughness
    vec4 film;       // x: the iridescent film's thickness (nm)
    // The normal map the trace reads at its hits: x its index among uTracedNormalMaps (-1:
    // none), y its scale, z its texture coordinate set; its KHR_texture_transform's rows.
    vec4 normalMap;
    vec4 normalUv[2];
};
layout(std430, binding = GLASS_MATERIALS_BINDING) readonly buffer GlassMaterials { GlassMaterial glassMaterials[]; };

#endif
