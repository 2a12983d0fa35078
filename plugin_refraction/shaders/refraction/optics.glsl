// Dielectric optics shared by the refraction methods: Fresnel, refraction with total internal
// reflection reported, the exit policies.
#ifndef REFRACTION_OPTICS_GLSL
#define REFRACTION_OPTICS_GLSL

// FRESNEL_EXACT, _SCHLICK, _OFF: the fresnel parameter's choices (Shared.h).

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

#endif
