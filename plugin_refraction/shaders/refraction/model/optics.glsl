// The optical model of glass (docs/methods.md, "The optical model") on the GPU, one function
// per rule, shared by the walk and the trace (walk.glsl): the reflectance of an interface, the
// media a path is in, the crossing of an interface, the microfacet normals of rough glass. Its
// C++ twin is GlassModel.cpp, the reference's; the two follow the same rules, line for line.
#ifndef REFRACTION_OPTICS_GLSL
#define REFRACTION_OPTICS_GLSL
#include "common/brdf.glsl"
#include "refraction/model/glass_materials.glsl"

// FRESNEL_EXACT, _SCHLICK, _OFF: the fresnel parameter's choices (Shared.h).
uniform int uFresnelMode;

// The parts of the interface model a program compiles (the plugin's variants, from the frame's
// glass; a program built without them keeps both): GLASS_SPECULAR, some glass has
// KHR_materials_specular's colour or weight; GLASS_FILM, some glass has an iridescent film.
#ifndef GLASS_SPECULAR
#define GLASS_SPECULAR 1
#endif
#ifndef GLASS_FILM
#define GLASS_FILM 1
#endif

// Unpolarised reflectance of a dielectric interface; cosI > 0, eta = n_incident / n_transmitted.
float fresnelExact(float cosI, float eta) {
    float sin2T = eta * eta * (1.0 - cosI * cosI);
    if (sin2T >= 1.0)
        return 1.0;
    float cosT = sqrt(1.0 - sin2T);
    float rs = (eta * cosI - cosT) / (eta * cosI + cosT);
    float rp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

float fresnel(int mode, float cosI, float eta) {
    if (mode == FRESNEL_OFF)
        return 0.0;
    if (mode == FRESNEL_SCHLICK) {
        float f0 = (1.0 - eta) / (1.0 + eta);
        f0 *= f0;
        return f0 + (1.0 - f0) * pow(1.0 - clamp(cosI, 0.0, 1.0), 5.0);
    }
    return fresnelExact(clamp(cosI, 0.0, 1.0), eta);
}

// Refracts unit direction I at a surface with unit normal N facing against I (dot(I, N) < 0).
// Returns false on total internal reflection.
bool refractRay(vec3 I, vec3 N, float eta, out vec3 T) {
    float cosI = -dot(I, N);
    float k = 1.0 - eta * eta * (1.0 - cosI * cosI);
    if (k < 0.0) {
        T = vec3(0.0);
        return false;
    }
    T = normalize(eta * I + (eta * cosI - sqrt(k)) * N);
    return true;
}

// The papers' TIR clamp: the incidence angle is clamped to the critical angle, so the ray
// leaves tangent to the exit surface (outward normal No).
vec3 tangentExit(vec3 I, vec3 No) {
    vec3 t = I - dot(I, No) * No;
    return length(t) > 1e-6 ? normalize(t) : No;
}
// At an exit ISR estimated (near the far side, not on it) the normal read may be tens of degrees
// off: only incidences this far past the critical angle reflect totally there.
const float kEstimatedTirBand = radians(20.0);

// The reflectance of an interface of glass m (its surface s there), from a medium of index n1
// into one of n2 (eta = n1 / n2), at cosI: the Fresnel mode's, its F0 coloured and weighted by
// KHR_materials_specular (the rise toward grazing kept), through the iridescent film, toward
// the base colour by metallic.
vec3 reflectance(GlassMaterial m, GlassSurface s, float cosI, float eta) {
#ifdef SKIP_INTERFACE // glass-bench --skip interface: a constant reflectance
    return vec3(0.04);
#endif
    vec3 F = vec3(fresnel(uFresnelMode, cosI, eta));
#if GLASS_SPECULAR
    if (m.specularColor != vec3(1.0) || m.specularWeight != 1.0) {
        float f0 = fresnel(uFresnelMode, 1.0, eta);
        vec3 coloured = min(f0 * m.specularColor, vec3(1.0));
        F = m.specularWeight *
            (coloured + (1.0 - coloured) * (f0 < 1.0 ? (F - f0) / (1.0 - f0) : vec3(1.0)));
    }
#endif
#if GLASS_FILM
    if (m.iridescence > 0.0 && uFresnelMode != FRESNEL_OFF)
        F = mix(F, thinFilmReflectance(cosI, m.iridescenceIor, m.filmThickness, vec3(1.0 / eta)),
                m.iridescence);
#endif
    return mix(F, s.baseColor, s.metallic);
}

// The media around a path: x up to MAX_MEDIA glass ids + 1, a byte each, the newest in the low
// byte (0: air); y the solid of each, byte for byte. A fifth nested glass is not entered (its
// crossings pass straight).
uint topMedium(uvec2 media) {
    return media.x & 255u;
}

uint solidOf(uint medium) {
    return glassMaterials[medium - 1u].solid;
}

bool containsSolid(uvec2 media, uint solid) {
    for (int k = 0; k < MAX_MEDIA; ++k)
        if (((media.x >> (8 * k)) & 255u) != 0u && ((media.y >> (8 * k)) & 255u) == solid)
            return true;
    return false;
}

// Crossing a surface of `medium` (glass id + 1) against its outward normal enters it; along it
// leaves the most recent entry of the same solid (character), if any.
uvec2 crossMedium(uvec2 media, uint medium, bool entering) {
    uint solid = solidOf(medium);
    if (entering)
        return (media.x >> 24) != 0u ? media : (media << 8) | uvec2(medium, solid);
    for (int k = 0; k < MAX_MEDIA; ++k) {
        if (((media.x >> (8 * k)) & 255u) != 0u && ((media.y >> (8 * k)) & 255u) == solid) {
            uvec2 below = k == 0 ? uvec2(0u) : media & uvec2((1u << (8 * k)) - 1u);
            uvec2 above = k == MAX_MEDIA - 1 ? uvec2(0u) : (media >> (8 * k + 8)) << (8 * k);
            return below | above;
        }
    }
    return media;
}

float mediumIor(uint medium, int channel) {
    return medium == 0u ? 1.0 : glassMaterials[medium - 1u].ior[channel];
}

// One path through the glass in one channel (a walk's or a trace's branch): where it is, where
// it goes, the light it carries and what it is in.
struct Path {
    vec3 P, dir;
    vec3 weight;
    uvec2 media;
    float ior;   // the medium's index (air: 1)
    vec3 sigma;  // its absorption
    float roughness; // the roughest interface crossed (a lookup's blur)
    int interfaces;  // crossed or reflected at, the entry included
    int crossings;   // surfaces crossed in all, passes included
    int splits;      // times it split (SPLIT_DEPTH)
};

// The glass whose surface a path meets: its glass id + 1, its surface there, and whether the
// path enters it (against the outward face).
struct SurfaceMet {
    uint medium;
    GlassSurface surface;
    bool enters;
};

// What crossing a surface did to a path (crossInterface).
const int CROSSED_PASSED = 0, CROSSED_REFRACTED = 1, CROSSED_REFLECTED = 2, CROSSED_GRAZING = 3;

// Crosses the surface `met` at the path's point with facet normal m (the shading normal, or a
// sampled microfacet's) in channel `channel`: the media change, and where the index changes,
// refraction (or total internal reflection) about m; a path entering a solid it is not in
// takes its surface's tint (base colour x transmission x (1 - metallic)) as well as 1 - F at an
// interface into glass, F then the share `reflected` (the caller's to follow or look up along
// reflect(dir, m)). Absorption along the segment before is the caller's. The walk's
// approximations ride in two arguments the trace and the reference leave off (band 0,
// mayReflect true): a total internal reflection within `band` past the critical angle, or
// where the walk may not reflect, leaves grazing (CROSSED_GRAZING, the papers' clamp).
int crossInterface(inout Path path, SurfaceMet met, vec3 m, int channel, float band,
                   bool mayReflect, out vec3 reflected) {
    reflected = vec3(0.0);
    ++path.crossings;
    bool newSolid = met.enters && !containsSolid(path.media, solidOf(met.medium));
    uvec2 after = crossMedium(path.media, met.medium, met.enters);
    uint to = topMedium(after);
    float n1 = path.ior, n2 = mediumIor(to, channel);
    GlassSurface s = met.surface;
    vec3 tint = newSolid ? s.baseColor * s.transmission * (1.0 - s.metallic) : vec3(1.0);
    if (n1 == n2) { // no interface: straight on (a new solid's surface still tints)
        path.weight *= tint;
        path.media = after;
        path.sigma = to == 0u ? vec3(0.0) : glassMaterials[to - 1u].sigma;
        return CROSSED_PASSED;
    }
    ++path.interfaces;
    if (dot(m, path.dir) > 0.0)
        m = -m;
    vec3 T;
    bool grazing = false;
    if (!refractRay(path.dir, m, n1 / n2, T)) {
        float incidence = acos(clamp(dot(-path.dir, m), 0.0, 1.0));
        grazing = !mayReflect || incidence < asin(n2 / n1) + band;
        if (grazing) {
            T = tangentExit(path.dir, -m); // leave tangent to the surface
        } else {
            path.dir = reflect(path.dir, m); // still in its medium
            return CROSSED_REFLECTED;
        }
    } else if (to != 0u) { // into glass: Fresnel splits the light
        vec3 F = reflectance(glassMaterials[met.medium - 1u], s, dot(-path.dir, m), n1 / n2);
        reflected = path.weight * F;
        path.weight *= 1.0 - F;
    }
    path.weight *= tint;
    path.dir = T;
    path.media = after;
    path.ior = n2;
    path.sigma = to == 0u ? vec3(0.0) : glassMaterials[to - 1u].sigma;
    path.roughness = max(path.roughness, s.roughness);
    return grazing ? CROSSED_GRAZING : CROSSED_REFRACTED;
}

// Smith's G1 for GGX (alpha a) of direction v about facet m of macro normal n.
float smithG1(vec3 v, vec3 m, vec3 n, float a) {
    float vn = dot(v, n);
    if (dot(v, m) * vn <= 0.0)
        return 0.0;
    float cos2 = min(vn * vn, 1.0), tan2 = (1.0 - cos2) / max(cos2, 1e-12);
    return 2.0 / (1.0 + sqrt(1.0 + a * a * tan2));
}

// A GGX microfacet normal around n (alpha = roughness^2) as the view i (toward the viewer, on
// n's side) sees them, from two uniform numbers: the distribution of visible normals (Heitz
// 2018), pdf G1(i, m) |i.m| D(m) / |i.n|.
vec3 sampleMicrofacet(vec3 n, float roughness, vec3 i, vec2 u) {
    // In the frame of n: the view stretched to the unit hemisphere's, a point of the projected
    // disk (the half the view sees more of), back on the hemisphere, unstretched.
    float a = roughness * roughness;
    vec3 axis = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 tx = normalize(cross(axis, n)), ty = cross(n, tx);
    vec3 vh = normalize(vec3(a * dot(i, tx), a * dot(i, ty), dot(i, n)));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x), phi = 6.283185307 * u.y;
    float p1 = r * cos(phi), s = 0.5 * (1.0 + vh.z);
    float p2 = (1.0 - s) * sqrt(max(1.0 - p1 * p1, 0.0)) + s * r * sin(phi);
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(1.0 - p1 * p1 - p2 * p2, 0.0)) * vh;
    vec3 m = normalize(vec3(a * nh.x, a * nh.y, max(nh.z, 0.0)));
    return normalize(m.x * tx + m.y * ty + m.z * n);
}

// The weight of a path scattered to o about a facet m so sampled, Fresnel aside: the
// microfacet BSDF (Walter et al. 2007, Eq. 20-21, separable Smith G) over the pdf and the
// Jacobian, G1(o, m); 0 where o leaves on the wrong side of the macro surface.
float microfacetWeight(vec3 o, vec3 m, vec3 n, float roughness, bool transmitted) {
    float on = dot(o, n);
    if (transmitted ? on >= 0.0 : on <= 0.0)
        return 0.0;
    return smithG1(o, m, n, roughness * roughness);
}

// Uniform numbers in [0, 1) from a state that advances (a PCG hash, GlassModel's random01).
float random01(inout uint state) {
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return float((word >> 22u) ^ word) / 4294967296.0;
}

#endif
