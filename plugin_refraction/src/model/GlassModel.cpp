// The optical model of glass in C++ (docs/methods.md, "The optical model"): optics.glsl's twin.
#include "GlassModel.h"

#include "engine/render/CpuShading.h"

#include <algorithm>
#include <cmath>

namespace refraction::model {

double fresnel(Settings::Fresnel mode, double cosI, double eta) {
    if (mode == Settings::Fresnel::Off)
        return 0.0;
    cosI = std::clamp(cosI, 0.0, 1.0);
    if (mode == Settings::Fresnel::Schlick) {
        const double f0 = ((1 - eta) / (1 + eta)) * ((1 - eta) / (1 + eta));
        return f0 + (1 - f0) * std::pow(1 - cosI, 5.0);
    }
    const double sin2T = eta * eta * (1 - cosI * cosI);
    if (sin2T >= 1)
        return 1.0;
    const double cosT = std::sqrt(1 - sin2T);
    const double rs = (eta * cosI - cosT) / (eta * cosI + cosT),
                 rp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

bool refract(const dvec3& i, const dvec3& n, double eta, dvec3& t) {
    const double cosI = -glm::dot(i, n), k = 1 - eta * eta * (1 - cosI * cosI);
    if (k < 0)
        return false;
    t = glm::normalize(eta * i + (eta * cosI - std::sqrt(k)) * n);
    return true;
}

double reflectance(Settings::Fresnel mode, const Optics& o, const GlassSurface& s, double cosI,
                   double eta, int c) {
    double F = fresnel(mode, cosI, eta);
    if (o.specularColor != glm::vec3(1.0f) || o.specularWeight != 1.0f) {
        const double f0 = fresnel(mode, 1.0, eta);
        const double coloured = std::min(f0 * o.specularColor[c], 1.0);
        F = o.specularWeight *
            (coloured + (1.0 - coloured) * (f0 < 1.0 ? (F - f0) / (1.0 - f0) : 1.0));
    }
    if (o.iridescence > 0.0f && mode != Settings::Fresnel::Off)
        F = glm::mix(F,
                     render::cpu::thinFilmReflectance(cosI, o.iridescenceIor,
                                                      o.iridescenceThickness, dvec3(1.0 / eta))[c],
                     double(o.iridescence));
    return glm::mix(F, s.baseColor[c], s.metallic);
}

bool Media::contains(int solid) const {
    for (int k = 0; k < mCount; ++k)
        if (mSolid[std::size_t(k)] == solid)
            return true;
    return false;
}

void Media::enter(const Optics* glass, int solid) {
    if (mCount == kMaxMedia)
        return; // a fifth nested glass is not entered
    mGlass[std::size_t(mCount)] = glass;
    mSolid[std::size_t(mCount)] = solid;
    ++mCount;
}

void Media::leave(int solid) {
    for (int k = mCount - 1; k >= 0; --k)
        if (mSolid[std::size_t(k)] == solid) {
            for (int j = k; j + 1 < mCount; ++j) {
                mGlass[std::size_t(j)] = mGlass[std::size_t(j + 1)];
                mSolid[std::size_t(j)] = mSolid[std::size_t(j + 1)];
            }
            --mCount;
            return;
        }
}

Crossed crossInterface(Path& path, const SurfaceMet& met, dvec3 m, int c, Settings::Fresnel mode,
                       double& reflected) {
    reflected = 0.0;
    ++path.crossings;
    const bool newSolid = met.enters && !path.media.contains(met.solid);
    Media after = path.media;
    if (met.enters)
        after.enter(met.optics, met.solid);
    else
        after.leave(met.solid);
    const Optics* to = after.top();
    const double n1 = path.ior, n2 = to ? double(to->ior[c]) : 1.0;
    const GlassSurface& s = met.surface;
    const double tint = newSolid ? s.baseColor[c] * s.transmission * (1.0 - s.metallic) : 1.0;
    if (n1 == n2) { // no interface: straight on (a new solid's surface still tints)
        path.weight *= tint;
        path.media = after;
        path.sigma = to ? double(to->sigma[c]) : 0.0;
        return Crossed::Passed;
    }
    ++path.interfaces;
    if (glm::dot(m, path.dir) > 0.0)
        m = -m;
    dvec3 t;
    if (!refract(path.dir, m, n1 / n2, t)) {
        path.dir = glm::reflect(path.dir, m); // still in its medium
        return Crossed::Reflected;
    }
    if (to) { // into glass: Fresnel splits the light
        const double F = reflectance(mode, *met.optics, s, -glm::dot(path.dir, m), n1 / n2, c);
        reflected = path.weight * F;
        path.weight *= 1.0 - F;
    }
    path.weight *= tint;
    path.dir = t;
    path.media = after;
    path.ior = n2;
    path.sigma = to ? double(to->sigma[c]) : 0.0;
    path.roughness = std::max(path.roughness, s.roughness);
    return Crossed::Refracted;
}

namespace {

/** Smith's G1 for GGX (alpha a) of direction v about facet m of macro normal n. */
double smithG1(const dvec3& v, const dvec3& m, const dvec3& n, double a) {
    const double vn = glm::dot(v, n);
    if (glm::dot(v, m) * vn <= 0.0)
        return 0.0;
    const double cos2 = std::min(vn * vn, 1.0), tan2 = (1.0 - cos2) / std::max(cos2, 1e-12);
    return 2.0 / (1.0 + std::sqrt(1.0 + a * a * tan2));
}

} // namespace

std::pair<dvec3, dvec3> tangentFrame(const dvec3& n) {
    const dvec3 axis = std::abs(n.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    const dvec3 tx = glm::normalize(glm::cross(axis, n));
    return {tx, glm::cross(n, tx)};
}

dvec3 sampleMicrofacet(const dvec3& n, double roughness, const dvec3& i, double u1, double u2) {
    // In the frame of n: the view stretched to the unit hemisphere's, a point of the projected
    // disk (the half the view sees more of), back on the hemisphere, unstretched.
    const double a = roughness * roughness;
    const auto [tx, ty] = tangentFrame(n);
    const dvec3 local(glm::dot(i, tx), glm::dot(i, ty), glm::dot(i, n));
    const dvec3 vh = glm::normalize(dvec3(a * local.x, a * local.y, local.z));
    const double lensq = vh.x * vh.x + vh.y * vh.y;
    const dvec3 t1 = lensq > 0.0 ? dvec3(-vh.y, vh.x, 0.0) / std::sqrt(lensq) : dvec3(1, 0, 0);
    const dvec3 t2 = glm::cross(vh, t1);
    const double r = std::sqrt(u1), phi = 2.0 * M_PI * u2;
    const double p1 = r * std::cos(phi), s = 0.5 * (1.0 + vh.z);
    const double p2 = (1.0 - s) * std::sqrt(std::max(1.0 - p1 * p1, 0.0)) + s * r * std::sin(phi);
    const dvec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(1.0 - p1 * p1 - p2 * p2, 0.0)) * vh;
    const dvec3 m = glm::normalize(dvec3(a * nh.x, a * nh.y, std::max(nh.z, 0.0)));
    return glm::normalize(m.x * tx + m.y * ty + m.z * n);
}

double microfacetWeight(const dvec3& o, const dvec3& m, const dvec3& n, double roughness,
                        bool transmitted) {
    const double on = glm::dot(o, n);
    if (transmitted ? on >= 0.0 : on <= 0.0)
        return 0.0;
    return smithG1(o, m, n, roughness * roughness);
}

double random01(std::uint32_t& state) {
    state = state * 747796405u + 2891336453u;
    std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return double((word >> 22u) ^ word) / 4294967296.0;
}

} // namespace refraction::model
