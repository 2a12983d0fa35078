// The optics of the frame's glass, one entry per glass id (a character's material with its
// overrides: GlassMaterialGpu in GpuState.h, the same fields in the same order, filled by
// assignGlassIds), read by every shading pass through the id its glass carries. Textures
// multiply the factors where a path meets the surface (optics.glsl's GlassSurface): the
// capture reads the material's own, the trace the frame's traced textures (trace.glsl).
#ifndef REFRACTION_GLASS_MATERIALS_GLSL
#define REFRACTION_GLASS_MATERIALS_GLSL

// Which textures some glass of the frame has, where it has any (the plugin's variants; all
// where not given): a base colour; authored transmissive, a transmission or metallic-roughness
// texture. A CPU rasteriser reads a texture a branch skips all the same, so the reads of the
// others are out.
#ifndef GLASS_BASE_COLOR_TEXTURES
#define GLASS_BASE_COLOR_TEXTURES 1
#endif
#ifndef GLASS_TRANSMISSION_TEXTURES
#define GLASS_TRANSMISSION_TEXTURES 1
#endif

// A texture the trace reads at its hits: its KHR_texture_transform's rows, its unit among
// TRACED_TEXTURES_UNIT's (-1: none) and its texture coordinate set.
struct TracedTexture {
    vec3 row0;
    int unit;
    vec3 row1;
    int uvSet;
};

struct GlassMaterial {
    vec3 ior; // per channel (dispersion)
    float transmission;
    vec3 sigma; // Beer-Lambert absorption per world unit
    float roughness;
    vec3 baseColor;
    float metallic;
    vec3 emissive;
    uint solid; // the character it belongs to (the media rule)
    vec3 specularColor; // KHR_materials_specular (white and 1 without it)
    float specularWeight;
    vec3 sheenColor;
    float sheenRoughness;
    float clearcoat, clearcoatRoughness;
    float iridescence, iridescenceIor;
    float filmThickness; // the iridescent film's (nm)
    float normalScale;
    uint authored; // glass by its own transmission: its transmission and roughness textures count
    uint spare;
    TracedTexture normalTexture, baseColorTexture, metallicRoughnessTexture, transmissionTexture;
};
layout(std430, binding = GLASS_MATERIALS_BINDING) readonly buffer GlassMaterials {
    GlassMaterial glassMaterials[];
};

// A glass surface at one point: its material's factors times its textures there (forced glass:
// the base colour only, clear and not metallic).
struct GlassSurface {
    vec3 baseColor;
    float transmission, roughness, metallic;
};

GlassSurface materialSurface(GlassMaterial m) {
    return GlassSurface(m.baseColor, m.transmission, m.roughness, m.metallic);
}

// A surface in 64 bits, as the captures keep it (layers.glsl's LayerSurfaces, the pair's surface
// maps): the square roots of its base colour and its transmission, its roughness and metallic,
// 8 bits each.
uvec2 packSurface(GlassSurface s) {
    return uvec2(packUnorm4x8(vec4(sqrt(clamp(s.baseColor, 0.0, 1.0)), s.transmission)),
                 packUnorm4x8(vec4(s.roughness, s.metallic, 0.0, 0.0)));
}

GlassSurface unpackSurface(uvec2 bits) {
    vec4 a = unpackUnorm4x8(bits.x), b = unpackUnorm4x8(bits.y);
    return GlassSurface(a.rgb * a.rgb, a.a, b.x, b.y);
}

#endif
