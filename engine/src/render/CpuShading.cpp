// The CPU twin of the GPU's material model (engine/render/CpuShading.h).
#include "engine/render/CpuShading.h"

#include "engine/render/Environment.h"
#include "engine/render/Lighting.h"

#include <algorithm>
#include <cmath>

namespace render {

using glm::dvec2;
using glm::dvec3;
using glm::dvec4;

// ---- The environment, as render/prefilter.comp.glsl and common/environment.glsl leave it

EnvironmentSampler::EnvironmentSampler(const asset::HdrImage& image, float rotation,
                                       float intensity)
    : mRotation(rotation), mIntensity(intensity) {
    Level level{image.width, image.height,
                std::vector<float>(std::size_t(image.width) * std::size_t(image.height) * 4, 1.0f)};
    for (std::size_t i = 0; i < std::size_t(image.width) * std::size_t(image.height); ++i)
        for (int c = 0; c < 3; ++c)
            level.rgba[i * 4 + std::size_t(c)] = image.rgb[i * 3 + std::size_t(c)];
    mLevels.push_back(std::move(level));
    mIrradiance = Level{1, 1, {0.0f, 0.0f, 0.0f, 1.0f}};
}

EnvironmentSampler EnvironmentSampler::fromGpu(const render::Environment& environment,
                                               float rotation, float intensity) {
    EnvironmentSampler s;
    s.mRotation = rotation;
    s.mIntensity = intensity;
    const gl::Texture& prefiltered = environment.prefiltered();
    for (int level = 0; level < prefiltered.levels(); ++level)
        s.mLevels.push_back({prefiltered.size(level).x, prefiltered.size(level).y,
                             prefiltered.downloadFloat(level)});
    const gl::Texture& irradiance = environment.irradiance();
    s.mIrradiance = {irradiance.size().x, irradiance.size().y, irradiance.downloadFloat(0)};
    return s;
}

dvec3 EnvironmentSampler::rotate(dvec3 d) const {
    const double c = std::cos(mRotation), s = std::sin(mRotation);
    return glm::normalize(dvec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z));
}

dvec3 EnvironmentSampler::bilinear(const Level& level, dvec2 uv) {
    const double x = uv.x * level.width - 0.5, y = uv.y * level.height - 0.5;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    dvec3 sum(0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) { // GL_REPEAT on both axes, as the GPU samples it
            const int xi = ((x0 + i) % level.width + level.width) % level.width;
            const int yi = ((y0 + j) % level.height + level.height) % level.height;
            const float* p =
                &level.rgba[(std::size_t(yi) * std::size_t(level.width) + std::size_t(xi)) * 4];
            sum += (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * dvec3(p[0], p[1], p[2]);
        }
    return sum;
}

namespace {

dvec2 equirectUv(dvec3 d) {
    return {0.5 + std::atan2(d.x, -d.z) / (2.0 * M_PI),
            std::acos(std::clamp(d.y, -1.0, 1.0)) / M_PI};
}

} // namespace

dvec3 EnvironmentSampler::radiance(dvec3 direction, double roughness) const {
    const dvec2 uv = equirectUv(rotate(direction));
    const double lod = std::clamp(roughness, 0.0, 1.0) * double(mLevels.size() - 1);
    const int l0 = int(std::floor(lod));
    const int l1 = std::min(l0 + 1, int(mLevels.size()) - 1);
    const double f = lod - l0;
    const dvec3 a = bilinear(mLevels[std::size_t(l0)], uv);
    return double(mIntensity) *
           (f > 0.0 ? glm::mix(a, bilinear(mLevels[std::size_t(l1)], uv), f) : a);
}

dvec3 EnvironmentSampler::irradiance(dvec3 normal) const {
    return double(mIntensity) * bilinear(mIrradiance, equirectUv(rotate(normal)));
}

namespace cpu {

// ---- Textures, as render/opaque.frag.glsl and common/material_uv.glsl read them

namespace {

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

} // namespace

glm::dvec4 sampleImage(const scene::Image& image, dvec2 uv, bool srgb) {
    if (image.pixels.empty() || image.width <= 0)
        return glm::dvec4(1.0);
    const double x = uv.x * image.width - 0.5, y = uv.y * image.height - 0.5;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    const std::size_t bytes = image.bitsPerChannel == 16 ? 2 : 1;
    glm::dvec4 sum(0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const int xi = ((x0 + i) % image.width + image.width) % image.width;
            const int yi = ((y0 + j) % image.height + image.height) % image.height;
            const std::size_t at =
                (std::size_t(yi) * std::size_t(image.width) + std::size_t(xi)) * 4 * bytes;
            glm::dvec4 texel;
            for (int c = 0; c < 4; ++c)
                texel[c] = double(image.pixels[at + std::size_t(c) * bytes + (bytes - 1)]) / 255.0;
            if (srgb)
                for (int c = 0; c < 3; ++c)
                    texel[c] = srgbToLinear(texel[c]);
            sum += (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * texel;
        }
    return sum;
}

const scene::Image* textureImage(const scene::Model& model, const scene::TextureRef& t) {
    if (!t.present())
        return nullptr;
    const int i = model.textures[std::size_t(t.texture)].image;
    return i >= 0 ? &model.images[std::size_t(i)] : nullptr;
}

dvec2 textureUv(const scene::TextureRef& t, glm::dvec4 uvs) {
    const dvec2 uv = t.texCoord == 1 ? dvec2(uvs.z, uvs.w) : dvec2(uvs);
    return dvec2(glm::dmat3(t.transform) * glm::dvec3(uv, 1.0));
}

dvec3 perturbNormal(const scene::TextureRef& map, const scene::Image& image, dvec3 N,
                    glm::dvec4 tangent, glm::dvec4 uv) {
    const dvec3 T = glm::normalize(dvec3(tangent) - N * glm::dot(N, dvec3(tangent)));
    const dvec3 B = glm::cross(N, T) * tangent.w;
    dvec3 n = dvec3(sampleImage(image, textureUv(map, uv), false)) * 2.0 - 1.0;
    n.x *= double(map.scale);
    n.y *= double(map.scale);
    const dvec3 mapped = T * n.x + B * n.y + N * n.z;
    return glm::length(mapped) > 1e-12 ? glm::normalize(mapped) : N;
}

// ---- Shading, as common/brdf.glsl and common/lighting.glsl shade

dvec2 environmentBrdf(double NoV, double roughness) {
    const dvec4 c0(-1.0, -0.0275, -0.572, 0.022), c1(1.0, 0.0425, 1.04, -0.04);
    const dvec4 r = roughness * c0 + c1;
    const double a004 = std::min(r.x * r.x, std::exp2(-9.28 * NoV)) * r.x + r.y;
    return dvec2(-1.04, 1.04) * a004 + dvec2(r.z, r.w);
}

namespace {

dvec3 iorFromF0(dvec3 f0) {
    const dvec3 r = glm::sqrt(glm::clamp(f0, dvec3(0.0), dvec3(0.9999)));
    return (1.0 + r) / (1.0 - r);
}

dvec3 schlick(dvec3 f0, double cosTheta) {
    return f0 + (1.0 - f0) * std::pow(1.0 - std::clamp(cosTheta, 0.0, 1.0), 5.0);
}

double maxOf(dvec3 v) {
    return std::max(v.r, std::max(v.g, v.b));
}

/** The GGX lobe stretched: alpha `at` along T, `ab` along B. */
double ggxLobe(dvec3 N, dvec3 T, dvec3 B, dvec3 L, dvec3 V, dvec3 H, double at, double ab) {
    const double NoL = std::max(glm::dot(N, L), 1e-4), NoV = std::max(glm::dot(N, V), 1e-4);
    const double d = std::pow(glm::dot(T, H) / at, 2.0) + std::pow(glm::dot(B, H) / ab, 2.0) +
                     std::pow(std::max(glm::dot(N, H), 0.0), 2.0);
    const double lv = NoL * glm::length(dvec3(at * glm::dot(T, V), ab * glm::dot(B, V), NoV));
    const double ll = NoV * glm::length(dvec3(at * glm::dot(T, L), ab * glm::dot(B, L), NoL));
    return 0.5 / (M_PI * at * ab * d * d * (lv + ll));
}

double sheenLobe(double NoL, double NoV, double NoH, double roughness) {
    const double r = std::max(roughness, 0.07), alpha = r * r;
    const double sinH = std::sqrt(std::max(1.0 - NoH * NoH, 0.0));
    const double D = (2.0 + 1.0 / alpha) * std::pow(sinH, 1.0 / alpha) / (2.0 * M_PI);
    return D / (4.0 * (NoL + NoV - NoL * NoV));
}

} // namespace

dvec3 thinFilmReflectance(double cosI, double film, double nm, dvec3 substrate) {
    const dvec3 wavelength(630.0, 532.0, 465.0);
    const double sin2I = 1.0 - cosI * cosI;
    const double cosF = std::sqrt(std::max(1.0 - sin2I / (film * film), 0.0));
    const dvec3 cosS = glm::sqrt(glm::max(1.0 - sin2I / (substrate * substrate), dvec3(0.0)));
    const double r12s = (cosI - film * cosF) / (cosI + film * cosF);
    const double r12p = (film * cosI - cosF) / (film * cosI + cosF);
    const dvec3 r23s = (film * cosF - substrate * cosS) / (film * cosF + substrate * cosS);
    const dvec3 r23p = (substrate * cosF - film * cosS) / (substrate * cosF + film * cosS);
    const dvec3 c = glm::cos(4.0 * M_PI * film * nm * cosF / wavelength);
    const dvec3 Rs = (r12s * r12s + r23s * r23s + 2.0 * r12s * r23s * c) /
                     (1.0 + r12s * r12s * r23s * r23s + 2.0 * r12s * r23s * c);
    const dvec3 Rp = (r12p * r12p + r23p * r23p + 2.0 * r12p * r23p * c) /
                     (1.0 + r12p * r12p * r23p * r23p + 2.0 * r12p * r23p * c);
    return glm::clamp(0.5 * (Rs + Rp), 0.0, 1.0);
}

double ggxLobe(double NoL, double NoV, double NoH, double a) {
    const double a2 = a * a, d = NoH * NoH * (a2 - 1.0) + 1.0;
    const double visibility = 0.5 / (NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2) +
                                     NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2));
    return a2 / (M_PI * d * d) * visibility;
}

dvec3 lightArriving(const scene::PlacedLight& placed, dvec3 P, dvec3& L) {
    const scene::Light& light = placed.light;
    const dvec3 radiance = dvec3(light.color) * double(light.intensity);
    if (light.type == scene::Light::Type::Directional) {
        L = -dvec3(placed.direction);
        return radiance;
    }
    const dvec3 toLight = dvec3(placed.position) - P;
    const double d2 = std::max(glm::dot(toLight, toLight), 1e-8);
    L = toLight / std::sqrt(d2);
    double falloff = 1.0 / d2;
    if (light.range > 0.0f) {
        const double x = d2 / (double(light.range) * double(light.range));
        const double window = std::clamp(1.0 - x * x, 0.0, 1.0);
        falloff *= window * window;
    }
    if (light.type == scene::Light::Type::Spot)
        falloff *= spotFalloff(placed, L);
    return radiance * falloff;
}

double spotFalloff(const scene::PlacedLight& placed, dvec3 L) {
    const scene::Light& light = placed.light;
    const double cosOuter = std::cos(double(light.outerConeAngle));
    const double cosInner = std::cos(double(light.innerConeAngle));
    const double t = std::clamp((glm::dot(dvec3(placed.direction), -L) - cosOuter) /
                                    std::max(cosInner - cosOuter, 1e-4),
                                0.0, 1.0);
    return t * t;
}

Surface readSurface(const scene::Model& model, const scene::Material& m, const Point& p,
                    dvec3& emissive) {
    auto read = [&](const scene::TextureRef& t, bool srgb, dvec4 fallback) {
        const scene::Image* image = textureImage(model, t);
        return image ? sampleImage(*image, textureUv(t, p.uv), srgb) : fallback;
    };
    Surface s;
    s.baseColor = dvec3(dvec4(m.baseColorFactor) * read(m.baseColorTexture, true, dvec4(1.0)));
    const dvec4 mr = read(m.metallicRoughnessTexture, false, dvec4(1.0));
    s.metallic = std::clamp(double(m.metallicFactor) * mr.b, 0.0, 1.0);
    s.roughness = std::clamp(double(m.roughnessFactor) * mr.g, 0.03, 1.0);
    s.occlusion = m.occlusionTexture.present()
                      ? 1.0 + double(m.occlusionTexture.scale) *
                                  (read(m.occlusionTexture, false, dvec4(1.0)).r - 1.0)
                      : 1.0;
    emissive = dvec3(m.emissiveFactor) * double(m.emissiveStrength) *
               dvec3(read(m.emissiveTexture, true, dvec4(1.0)));
    if (m.hasSpecular) { // as MaterialTextures::bind: without it weight 1, colour white
        s.specularWeight = double(m.specularFactor) * read(m.specularTexture, false, dvec4(1.0)).a;
        s.dielectricF0 = double(m.dielectricF0()) * dvec3(m.specularColorFactor) *
                         dvec3(read(m.specularColorTexture, true, dvec4(1.0)));
    } else {
        s.dielectricF0 = dvec3(double(m.dielectricF0()));
    }
    s.clearcoatNormal = p.interpolatedNormal;
    if (m.hasClearcoat) {
        s.clearcoat = double(m.clearcoatFactor) * read(m.clearcoatTexture, false, dvec4(1.0)).r;
        s.clearcoatRoughness =
            std::clamp(double(m.clearcoatRoughnessFactor) *
                           read(m.clearcoatRoughnessTexture, false, dvec4(1.0)).g,
                       0.03, 1.0);
        if (const scene::Image* image = textureImage(model, m.clearcoatNormalTexture);
            image && p.tangent != dvec4(0.0))
            s.clearcoatNormal = perturbNormal(m.clearcoatNormalTexture, *image,
                                              p.interpolatedNormal, p.tangent, p.uv);
    }
    if (m.hasSheen) {
        s.sheenColor =
            dvec3(m.sheenColorFactor) * dvec3(read(m.sheenColorTexture, true, dvec4(1.0)));
        s.sheenRoughness =
            double(m.sheenRoughnessFactor) * read(m.sheenRoughnessTexture, false, dvec4(1.0)).a;
    }
    if (m.hasIridescence) {
        s.iridescence =
            double(m.iridescenceFactor) * read(m.iridescenceTexture, false, dvec4(1.0)).r;
        s.iridescenceIor = m.iridescenceIor;
        s.iridescenceThickness =
            m.iridescenceThicknessTexture.present()
                ? glm::mix(double(m.iridescenceThicknessMinimum),
                           double(m.iridescenceThicknessMaximum),
                           read(m.iridescenceThicknessTexture, false, dvec4(1.0)).g)
                : double(m.iridescenceThicknessMaximum);
    }
    if (m.hasAnisotropy && m.anisotropyStrength > 0.0f && p.tangent != dvec4(0.0)) {
        const dvec3 a = dvec3(read(m.anisotropyTexture, false, dvec4(1.0, 0.5, 1.0, 1.0)));
        const dvec2 d0 = dvec2(a) * 2.0 - 1.0;
        const double c = std::cos(double(m.anisotropyRotation)),
                     sn = std::sin(double(m.anisotropyRotation));
        const dvec2 d(c * d0.x - sn * d0.y, sn * d0.x + c * d0.y);
        const dvec3 N = p.normal;
        const dvec3 T = glm::normalize(dvec3(p.tangent) - N * glm::dot(N, dvec3(p.tangent)));
        const dvec3 B = glm::cross(N, T) * p.tangent.w;
        const dvec3 direction = T * d.x + B * d.y;
        if (glm::dot(direction, direction) > 1e-8) {
            s.anisotropy = std::clamp(double(m.anisotropyStrength) * a.b, 0.0, 1.0);
            s.anisotropyDirection = glm::normalize(direction);
        }
    }
    return s;
}

dvec3 lightArriving(const Lighting& lighting, std::size_t i, dvec3 P, dvec3 N, dvec3& L) {
    const dvec3 arriving = lightArriving(lighting.lights[i], P, L);
    if (!lighting.visibility || arriving == dvec3(0.0))
        return arriving;
    return arriving * lighting.visibility(i, P, N, L);
}

dvec3 layersOver(dvec3 under, const Surface& s, const Lighting& lighting, dvec3 P, dvec3 N,
                 dvec3 V) {
    const bool sheenLayer = maxOf(s.sheenColor) > 0.0, coatLayer = s.clearcoat > 0.0;
    if (!sheenLayer && !coatLayer)
        return under;
    const double NoV = std::clamp(glm::dot(N, V), 1e-4, 1.0);
    const double sheenE = sheenLayer ? sheenAlbedo(NoV, s.sheenRoughness) : 0.0;
    dvec3 sheen = sheenLayer
                      ? s.sheenColor * lighting.environment.irradiance(N) * sheenE * s.occlusion
                      : dvec3(0.0);
    const dvec3 Nc = s.clearcoatNormal;
    const double NoVc = std::clamp(glm::dot(Nc, V), 1e-4, 1.0);
    const double coatAlpha = std::max(s.clearcoatRoughness * s.clearcoatRoughness, 1e-3);
    dvec3 coat(0.0);
    if (coatLayer) {
        const dvec2 dfg = environmentBrdf(NoVc, s.clearcoatRoughness);
        coat = lighting.environment.radiance(glm::reflect(-V, Nc), s.clearcoatRoughness) *
               (0.04 * dfg.x + dfg.y) * s.occlusion;
    }
    for (std::size_t i = 0; i < lighting.lights.size(); ++i) {
        dvec3 L;
        const dvec3 arriving = lightArriving(lighting, i, P, N, L);
        const dvec3 H = glm::normalize(L + V);
        const double NoL = glm::dot(N, L), NoLc = glm::dot(Nc, L);
        if (sheenLayer && NoL > 0.0)
            sheen += arriving * NoL * s.sheenColor *
                     sheenLobe(NoL, NoV, std::max(glm::dot(N, H), 0.0), s.sheenRoughness);
        if (coatLayer && NoLc > 0.0)
            coat += arriving * NoLc * schlick(dvec3(0.04), std::max(glm::dot(V, H), 0.0)) *
                    ggxLobe(NoLc, NoVc, std::max(glm::dot(Nc, H), 0.0), coatAlpha);
    }
    const dvec3 color = under * (1.0 - maxOf(s.sheenColor) * sheenE) + sheen;
    const double coatFresnel = 0.04 + 0.96 * std::pow(1.0 - NoVc, 5.0);
    return color * (1.0 - s.clearcoat * coatFresnel) + s.clearcoat * coat;
}

dvec3 shadeSurface(const Surface& s, const Lighting& lighting, dvec3 P, dvec3 N, dvec3 V) {
    const double NoV = std::clamp(glm::dot(N, V), 1e-4, 1.0);
    const double alpha = std::max(s.roughness * s.roughness, 1e-3);
    dvec3 f0Dielectric = glm::min(s.dielectricF0, dvec3(1.0)), f0Metal = s.baseColor;
    if (s.iridescence > 0.0) {
        f0Dielectric = glm::mix(f0Dielectric,
                                thinFilmReflectance(NoV, s.iridescenceIor, s.iridescenceThickness,
                                                    iorFromF0(f0Dielectric)),
                                s.iridescence);
        f0Metal = glm::mix(
            f0Metal,
            thinFilmReflectance(NoV, s.iridescenceIor, s.iridescenceThickness, iorFromF0(f0Metal)),
            s.iridescence);
    }
    const dvec3 T = s.anisotropyDirection, B = glm::cross(N, T);
    const double along = glm::mix(alpha, 1.0, s.anisotropy * s.anisotropy);
    dvec3 R = glm::reflect(-V, N);
    if (s.anisotropy > 0.0) {
        const dvec3 stretchedNormal = glm::cross(glm::cross(B, V), B);
        double bend = 1.0 - s.anisotropy * (1.0 - s.roughness);
        bend *= bend;
        R = glm::reflect(-V, glm::normalize(glm::mix(stretchedNormal, N, bend * bend)));
    }
    const dvec2 dfg = environmentBrdf(NoV, s.roughness);
    const dvec3 radiance = lighting.environment.radiance(R, s.roughness);
    const dvec3 dielectric = s.specularWeight * radiance * (f0Dielectric * dfg.x + dfg.y);
    const dvec3 metal = radiance * (f0Metal * dfg.x + dfg.y);
    dvec3 base = (lighting.environment.irradiance(N) * s.baseColor * (1.0 - s.metallic) +
                  glm::mix(dielectric, metal, s.metallic)) *
                 s.occlusion;
    for (std::size_t i = 0; i < lighting.lights.size(); ++i) {
        dvec3 L;
        const dvec3 arriving = lightArriving(lighting, i, P, N, L);
        const dvec3 H = glm::normalize(L + V);
        const double NoL = glm::dot(N, L), VoH = std::max(glm::dot(V, H), 0.0),
                     NoH = std::max(glm::dot(N, H), 0.0);
        if (NoL <= 0.0)
            continue;
        const double lobe = s.anisotropy > 0.0 ? ggxLobe(N, T, B, L, V, H, along, alpha)
                                               : ggxLobe(NoL, NoV, NoH, alpha);
        const dvec3 specular = glm::mix(s.specularWeight * schlick(f0Dielectric, VoH),
                                        schlick(f0Metal, VoH), s.metallic) *
                               lobe;
        base += arriving * NoL * (s.baseColor * (1.0 - s.metallic) / M_PI + specular);
    }
    return layersOver(base, s, lighting, P, N, V);
}

std::vector<std::uint8_t> tonemap(std::span<const float> rgba, float exposure) {
    std::vector<std::uint8_t> out(rgba.size());
    for (std::size_t i = 0; i < rgba.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c) {
            double x = std::max(0.0, double(rgba[i + c]) * exposure);
            x = std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
            x = x < 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
            out[i + c] = std::uint8_t(std::lround(std::clamp(x, 0.0, 1.0) * 255.0));
        }
        out[i + 3] = 255;
    }
    return out;
}

} // namespace cpu
} // namespace render
