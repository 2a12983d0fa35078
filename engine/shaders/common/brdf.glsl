// glTF's material model lit by the environment (split sum, analytic environment BRDF) and the
// punctual lights: metallic-roughness with the layers KHR_materials_specular, _clearcoat,
// _sheen, _iridescence and _anisotropy put on it. The Embree reference shades the same model
// (ReferenceTracer.cpp, "Shading shared with common/brdf.glsl").
#ifndef COMMON_BRDF_GLSL
#define COMMON_BRDF_GLSL
#include "common/environment.glsl"
#include "common/lighting.glsl"

// The layers compiled in (a program per set its materials use: a layer's code costs a CPU
// rasteriser even where it is switched off): clear coat, sheen, iridescence, anisotropy (the
// LAYER_* bits of scene::Material, render/Shared.h).
#ifndef SURFACE_LAYERS
#define SURFACE_LAYERS (LAYER_CLEARCOAT | LAYER_SHEEN | LAYER_IRIDESCENCE | LAYER_ANISOTROPY)
#endif

// Karis' analytic fit of the split-sum environment BRDF scale and bias.
vec2 environmentBrdf(float NoV, float roughness) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
    return vec2(-1.04, 1.04) * a004 + r.zw;
}

// A shaded point's material, its textures read (common/surface_material.glsl). Without the
// extensions: F0 0.04, specular weight 1, and no layer (coreSurface).
struct SurfaceMaterial {
    vec3 baseColor;
    float metallic, roughness, occlusion;
    vec3 dielectricF0;    // KHR_materials_specular: F0 from the ior times its colour
    float specularWeight; // and its factor
    float clearcoat, clearcoatRoughness;
    vec3 clearcoatNormal; // the coat's own normal (the geometric one without its map)
    vec3 sheenColor;
    float sheenRoughness;
    float iridescence, iridescenceIor, iridescenceThickness; // thickness in nanometres
    float anisotropy;          // strength
    vec3 anisotropyDirection;  // unit, in the tangent plane (world)
};

SurfaceMaterial coreSurface(vec3 baseColor, float metallic, float roughness, float occlusion,
                            vec3 N) {
    SurfaceMaterial m;
    m.baseColor = baseColor;
    m.metallic = metallic;
    m.roughness = roughness;
    m.occlusion = occlusion;
    m.dielectricF0 = vec3(0.04);
    m.specularWeight = 1.0;
    m.clearcoat = 0.0;
    m.clearcoatRoughness = 0.0;
    m.clearcoatNormal = N;
    m.sheenColor = vec3(0.0);
    m.sheenRoughness = 0.0;
    m.iridescence = 0.0;
    m.iridescenceIor = 1.3;
    m.iridescenceThickness = 0.0;
    m.anisotropy = 0.0;
    m.anisotropyDirection = vec3(0.0);
    return m;
}

// The index of refraction (against air) that reflects F0 at normal incidence.
vec3 iorFromF0(vec3 f0) {
    vec3 r = sqrt(clamp(f0, vec3(0.0), vec3(0.9999)));
    return (1.0 + r) / (1.0 - r);
}

// Thin-film interference (KHR_materials_iridescence): the reflectance, seen from air at cosI, of
// a film of index `film` and thickness `nm` nanometres over a substrate of index `substrate`,
// at each channel's wavelength: the two interfaces' amplitude coefficients summed over every
// internal bounce (Airy), s and p polarisations averaged.
vec3 thinFilmReflectance(float cosI, float film, float nm, vec3 substrate) {
    const vec3 wavelength = vec3(630.0, 532.0, 465.0);
    float sin2I = 1.0 - cosI * cosI;
    float cosF = sqrt(max(1.0 - sin2I / (film * film), 0.0));
    vec3 cosS = sqrt(max(1.0 - sin2I / (substrate * substrate), vec3(0.0)));
    float r12s = (cosI - film * cosF) / (cosI + film * cosF);
    float r12p = (film * cosI - cosF) / (film * cosI + cosF);
    vec3 r23s = (film * cosF - substrate * cosS) / (film * cosF + substrate * cosS);
    vec3 r23p = (substrate * cosF - film * cosS) / (substrate * cosF + film * cosS);
    vec3 c = cos(4.0 * PI * film * nm * cosF / wavelength);
    vec3 Rs = (r12s * r12s + r23s * r23s + 2.0 * r12s * r23s * c) /
              (1.0 + r12s * r12s * r23s * r23s + 2.0 * r12s * r23s * c);
    vec3 Rp = (r12p * r12p + r23p * r23p + 2.0 * r12p * r23p * c) /
              (1.0 + r12p * r12p * r23p * r23p + 2.0 * r12p * r23p * c);
    return clamp(0.5 * (Rs + Rp), 0.0, 1.0);
}

vec3 schlick(vec3 f0, float cosTheta) {
    return f0 + (1.0 - f0) * pow(1.0 - clamp(cosTheta, 0.0, 1.0), 5.0);
}

// GGX's distribution times the height-correlated Smith visibility, roughness alpha `a`.
float ggxLobe(float NoL, float NoV, float NoH, float a) {
    float a2 = a * a;
    float d = NoH * NoH * (a2 - 1.0) + 1.0;
    float visibility = 0.5 / (NoL * sqrt(NoV * NoV * (1.0 - a2) + a2) +
                              NoV * sqrt(NoL * NoL * (1.0 - a2) + a2));
    return a2 / (PI * d * d) * visibility;
}

// The same lobe stretched: alpha `at` along the tangent T, `ab` along the bitangent B.
float ggxLobe(vec3 N, vec3 T, vec3 B, vec3 L, vec3 V, vec3 H, float at, float ab) {
    float NoL = max(dot(N, L), 1e-4), NoV = max(dot(N, V), 1e-4);
    float d = pow(dot(T, H) / at, 2.0) + pow(dot(B, H) / ab, 2.0) + pow(max(dot(N, H), 0.0), 2.0);
    float lv = NoL * length(vec3(at * dot(T, V), ab * dot(B, V), NoV));
    float ll = NoV * length(vec3(at * dot(T, L), ab * dot(B, L), NoL));
    return 0.5 / (PI * at * ab * d * d * (lv + ll));
}

float maxOf(vec3 v) {
    return max(v.r, max(v.g, v.b));
}

// The sheen lobe (KHR_materials_sheen): the "Charlie" distribution with Ashikhmin's visibility.
float sheenLobe(float NoL, float NoV, float NoH, float roughness) {
    float alpha = max(roughness, 0.07) * max(roughness, 0.07);
    float sinH = sqrt(max(1.0 - NoH * NoH, 0.0));
    float D = (2.0 + 1.0 / alpha) * pow(sinH, 1.0 / alpha) / (2.0 * PI);
    return D / (4.0 * (NoL + NoV - NoL * NoV));
}

// `under`, the light a surface sends along V, seen through the layers the material puts on it:
// the sheen passes on all but its albedo and adds its lobe, the clear coat all but its Fresnel
// at the view and adds its reflection. Without layers, `under` itself.
vec3 layersOver(vec3 under, SurfaceMaterial m, vec3 P, vec3 N, vec3 V) {
#if (SURFACE_LAYERS & (LAYER_CLEARCOAT | LAYER_SHEEN)) == 0
    return under;
#endif
    bool sheenLayer = maxOf(m.sheenColor) > 0.0, coatLayer = m.clearcoat > 0.0;
    if (!sheenLayer && !coatLayer)
        return under;
    float NoV = clamp(dot(N, V), 1e-4, 1.0);
    float sheenE = sheenLayer ? sheenAlbedo(NoV, m.sheenRoughness) : 0.0;
    vec3 sheen = sheenLayer ? m.sheenColor * environmentIrradiance(N) * sheenE * m.occlusion
                            : vec3(0.0);
    vec3 Nc = m.clearcoatNormal;
    float NoVc = clamp(dot(Nc, V), 1e-4, 1.0);
    float coatAlpha = max(m.clearcoatRoughness * m.clearcoatRoughness, 1e-3);
    vec3 coat = vec3(0.0);
    if (coatLayer) {
        vec2 dfg = environmentBrdf(NoVc, m.clearcoatRoughness);
        coat = environmentRadiance(reflect(-V, Nc), m.clearcoatRoughness) *
               (0.04 * dfg.x + dfg.y) * m.occlusion;
    }
#if PUNCTUAL_LIGHTS
    for (uint i = 0u; i < lightCount.x; ++i) {
        vec3 L;
        vec3 arriving = lightArriving(i, P, N, L);
        vec3 H = normalize(L + V);
        float NoL = dot(N, L), NoLc = dot(Nc, L);
        if (sheenLayer && NoL > 0.0)
            sheen += arriving * NoL * m.sheenColor *
                     sheenLobe(NoL, NoV, max(dot(N, H), 0.0), m.sheenRoughness);
        if (coatLayer && NoLc > 0.0)
            coat += arriving * NoLc * schlick(vec3(0.04), max(dot(V, H), 0.0)) *
                    ggxLobe(NoLc, NoVc, max(dot(Nc, H), 0.0), coatAlpha);
    }
#endif
    vec3 color = under * (1.0 - maxOf(m.sheenColor) * sheenE) + sheen;
    float coatFresnel = 0.04 + 0.96 * pow(1.0 - NoVc, 5.0);
    return color * (1.0 - m.clearcoat * coatFresnel) + m.clearcoat * coat;
}

// The light the surface at P (normal N, toward the viewer V) sends back along V.
vec3 shadeSurface(SurfaceMaterial m, vec3 P, vec3 N, vec3 V) {
    float NoV = clamp(dot(N, V), 1e-4, 1.0);
    float alpha = max(m.roughness * m.roughness, 1e-3);
    // Reflectance at normal incidence of the dielectric and of the metal, seen through the film.
    vec3 f0Dielectric = min(m.dielectricF0, vec3(1.0)), f0Metal = m.baseColor;
#if (SURFACE_LAYERS & LAYER_IRIDESCENCE) != 0
    if (m.iridescence > 0.0) {
        f0Dielectric = mix(f0Dielectric,
                           thinFilmReflectance(NoV, m.iridescenceIor, m.iridescenceThickness,
                                               iorFromF0(f0Dielectric)),
                           m.iridescence);
        f0Metal = mix(f0Metal,
                      thinFilmReflectance(NoV, m.iridescenceIor, m.iridescenceThickness,
                                          iorFromF0(f0Metal)),
                      m.iridescence);
    }
#endif
    // Anisotropy stretches the lobe along its direction T (alpha `along`) and reads the
    // environment along the reflection off a normal bent toward T.
    vec3 T = m.anisotropyDirection, B = cross(N, T);
    float along = mix(alpha, 1.0, m.anisotropy * m.anisotropy);
    vec3 R = reflect(-V, N);
#if (SURFACE_LAYERS & LAYER_ANISOTROPY) != 0
    if (m.anisotropy > 0.0) {
        vec3 stretchedNormal = cross(cross(B, V), B);
        float bend = 1.0 - m.anisotropy * (1.0 - m.roughness);
        bend *= bend;
        R = reflect(-V, normalize(mix(stretchedNormal, N, bend * bend)));
    }
#endif

    vec2 dfg = environmentBrdf(NoV, m.roughness);
    vec3 radiance = environmentRadiance(R, m.roughness);
    vec3 irradiance = environmentIrradiance(N);
    vec3 dielectric = m.specularWeight * radiance * (f0Dielectric * dfg.x + dfg.y);
    vec3 metal = radiance * (f0Metal * dfg.x + dfg.y);
    vec3 base = (irradiance * m.baseColor * (1.0 - m.metallic) + mix(dielectric, metal, m.metallic)) *
                m.occlusion;
#if PUNCTUAL_LIGHTS
    for (uint i = 0u; i < lightCount.x; ++i) {
        vec3 L;
        vec3 arriving = lightArriving(i, P, N, L);
        vec3 H = normalize(L + V);
        float NoL = dot(N, L), VoH = max(dot(V, H), 0.0), NoH = max(dot(N, H), 0.0);
        if (NoL <= 0.0)
            continue;
#if (SURFACE_LAYERS & LAYER_ANISOTROPY) != 0
        float lobe = m.anisotropy > 0.0 ? ggxLobe(N, T, B, L, V, H, along, alpha)
                                        : ggxLobe(NoL, NoV, NoH, alpha);
#else
        float lobe = ggxLobe(NoL, NoV, NoH, alpha);
#endif
        vec3 specular = mix(m.specularWeight * schlick(f0Dielectric, VoH), schlick(f0Metal, VoH),
                            m.metallic) *
                        lobe;
        base += arriving * NoL * (m.baseColor * (1.0 - m.metallic) / PI + specular);
    }
#endif
    return layersOver(base, m, P, N, V);
}

// The core model with KHR_materials_specular's F0 and weight, no other layer.
vec3 shadeMetallicRoughnessSpecular(vec3 baseColor, float metallic, float roughness,
                                    float occlusion, vec3 P, vec3 N, vec3 V, vec3 dielectricF0,
                                    float specularWeight) {
    SurfaceMaterial m = coreSurface(baseColor, metallic, roughness, occlusion, N);
    m.dielectricF0 = dielectricF0;
    m.specularWeight = specularWeight;
    return shadeSurface(m, P, N, V);
}

vec3 shadeMetallicRoughness(vec3 baseColor, float metallic, float roughness, float occlusion,
                            vec3 P, vec3 N, vec3 V) {
    return shadeSurface(coreSurface(baseColor, metallic, roughness, occlusion, N), P, N, V);
}
#endif
