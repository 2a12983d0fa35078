// The walk's optics around its search (walk.glsl): Wyman's estimate of the exit distance,
// the shared dispersion search's red and blue rays, and the light at the entry (its
// reflectance with the reflected environment, tint, transmission, emission).
#ifndef REFRACTION_GLASS_SURFACE_GLSL
#define REFRACTION_GLASS_SURFACE_GLSL
#include "refraction/model/optics.glsl"
#include "refraction/passes/scene_lookup.glsl"

// GLASS_PARTIAL: some glass of the frame transmits only in part (its factor or texture), so
// the opaque term is compiled in (the plugin's variants; on where not given).
#ifndef GLASS_PARTIAL
#define GLASS_PARTIAL 1
#endif

// ISR (Wyman 2005): the distance along T1 from the entry to the estimated exit, d_V and d_N
// interpolated by theta_t / theta_i (d_V alone where no d_N was measured: dN < 0).
float wymanDistance(vec3 V, vec3 N1, vec3 T1, float eta, float dV, float dN) {
    float thetaI = acos(clamp(dot(-V, N1), -1.0, 1.0));
    float thetaT = acos(clamp(dot(T1, -N1), -1.0, 1.0));
    float ratio = thetaI > 1e-4 ? thetaT / thetaI : eta;
    return ratio * dV + (1.0 - ratio) * (dN >= 0.0 ? dN : dV);
}

// The shared dispersion search: one channel's ray leaves by green's last refraction (incoming
// direction, the normal facing it, eta for this channel) redone with the deviation its own
// entry refraction gave it; `otherwise` where it reflects totally.
vec3 channelExit(vec3 incoming, vec3 normal, float eta, vec3 deviation, vec3 otherwise) {
    vec3 T;
    return refractRay(normalize(incoming + deviation), normal, eta, T) ? T : otherwise;
}

// What that channel's ray sees from `point`: the scene where green's ray met it, hitT along
// (the lookup's hit distance, negative for the environment), on screen; off it, the ground
// where the ray meets it; else the environment.
vec3 channelSees(vec3 point, vec3 dir, float hitT, float roughness) {
    if (hitT < 0.0)
        return environmentRadiance(uViewToWorld * dir, roughness);
    vec3 X = point + dir * hitT;
    vec2 uv = projectToUv(X);
    if (X.z < 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0))))
        return texelFetch(uSceneColor, ivec2(uv * uViewportSize), 0).rgb;
#if NEARBY_GROUND
    float t = groundHit(point, dir);
    if (t > 0.0)
        return groundSeen(point, dir, t);
#endif
    return environmentRadiance(uViewToWorld * dir, roughness);
}

// The glass's colour at the entry P (view space; view direction V, normal N1 facing it, its
// surface s there) of light `transmitted` through it: its reflectance (optics.glsl, from air)
// between the reflected environment and the lights' highlights and the transmitted light in
// its tint, the opaque term where transmission is partial, the clear coat and sheen over it,
// and emission.
vec3 glassColor(GlassMaterial m, GlassSurface s, vec3 P, vec3 V, vec3 N1, vec3 transmitted) {
#ifdef SKIP_GLASS_COLOR // glass-bench --skip glass_color: the transmitted light alone
    return transmitted;
#endif
    vec3 Pw = uViewToWorld * P + uViewOriginWorld, Nw = uViewToWorld * N1, Vw = uViewToWorld * -V;
    float eta = 1.0 / m.ior.g;
    vec3 F = reflectance(m, s, dot(-V, N1), eta);
    vec3 reflected = environmentRadiance(uViewToWorld * reflect(V, N1), s.roughness);
    vec3 glass = F * reflected + (1.0 - F) * s.baseColor * (1.0 - s.metallic) * transmitted;
    float NoV = clamp(dot(Nw, Vw), 1e-4, 1.0);
    float alpha = max(s.roughness, 0.03) * max(s.roughness, 0.03);
    gCausticReceiver = false; // the glass's own light goes straight through it
#if PUNCTUAL_LIGHTS
    for (uint i = 0u; i < lightCount.x; ++i) {
        vec3 L;
        vec3 arriving = lightArriving(i, Pw, Nw, L);
        vec3 H = normalize(L + Vw);
        float NoL = dot(Nw, L);
        if (NoL > 0.0)
            glass += arriving * NoL * reflectance(m, s, max(dot(Vw, H), 0.0), eta) *
                     ggxLobe(NoL, NoV, max(dot(Nw, H), 0.0), alpha);
    }
#endif
    vec3 color = glass;
#if GLASS_PARTIAL
    if (s.transmission < 1.0) // clear glass skips the opaque term
        color = mix(shadeMetallicRoughness(s.baseColor, s.metallic, max(s.roughness, 0.03), 1.0,
                                           Pw, Nw, Vw),
                    glass, s.transmission);
#endif
    SurfaceMaterial layers = coreSurface(s.baseColor, s.metallic, s.roughness, 1.0, Nw);
    layers.clearcoat = m.clearcoat;
    layers.clearcoatRoughness = m.clearcoatRoughness;
    layers.sheenColor = m.sheenColor;
    layers.sheenRoughness = m.sheenRoughness;
    color = layersOver(color, layers, Pw, Nw, Vw) + m.emissive;
    gCausticReceiver = true;
    return color;
}

#endif
