// Embree reference tracer: glass with real TIR, the opaque scene and the ground shaded like the
// GPU's opaque pass, the environment sampled like the GPU's.
#include "refraction/ReferenceTracer.h"

#include "Optics.h"

#include "engine/deform/CpuDeformer.h"
#include "engine/render/Environment.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <thread>
#include <unistd.h>

namespace refraction {

using glm::dvec2;
using glm::dvec3;

// ---- Environment, as render/prefilter.comp.glsl and common/environment.glsl leave it

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

namespace {

// ---- Shading shared with render/pbr.frag.glsl and common/brdf.glsl

dvec2 environmentBrdf(double NoV, double roughness) {
    const glm::dvec4 c0(-1.0, -0.0275, -0.572, 0.022), c1(1.0, 0.0425, 1.04, -0.04);
    const glm::dvec4 r = roughness * c0 + c1;
    const double a004 = std::min(r.x * r.x, std::exp2(-9.28 * NoV)) * r.x + r.y;
    return dvec2(-1.04, 1.04) * a004 + dvec2(r.z, r.w);
}

/** As common/brdf.glsl: the dielectric's lobe with F0 `dielectricF0` (at most 1) and weight
 *  `specularWeight` (KHR_materials_specular), a metal's with its base colour. */
dvec3 shadeMetallicRoughness(const EnvironmentSampler& env, dvec3 base, double metallic,
                             double roughness, dvec3 N, dvec3 V, dvec3 dielectricF0 = dvec3(0.04),
                             double specularWeight = 1.0) {
    const double NoV = std::clamp(glm::dot(N, V), 1e-4, 1.0);
    const dvec2 ab = environmentBrdf(NoV, roughness);
    const dvec3 radiance = env.radiance(glm::reflect(-V, N), roughness);
    const dvec3 dielectric =
        specularWeight * radiance * (glm::min(dielectricF0, dvec3(1.0)) * ab.x + ab.y);
    const dvec3 metal = radiance * (base * ab.x + ab.y);
    const dvec3 diffuse = env.irradiance(N) * base * (1.0 - metallic);
    return diffuse + glm::mix(dielectric, metal, metallic);
}

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/** Bilinear RGBA of a glTF image at uv with wrapping (level 0; the GPU's mip filtering of
 *  distant texels is not reproduced). */
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

/** The image a material's texture reads, or null. */
const scene::Image* textureImage(const scene::Model& model, const scene::TextureRef& t) {
    if (!t.present())
        return nullptr;
    const int i = model.textures[std::size_t(t.texture)].image;
    return i >= 0 ? &model.images[std::size_t(i)] : nullptr;
}

/** uv through the texture's KHR_texture_transform. */
/** The texture coordinates `t` reads (of `uvs`: TEXCOORD_0 in xy, TEXCOORD_1 in zw, as
 *  common/material_uv.glsl), through its KHR_texture_transform. */
dvec2 textureUv(const scene::TextureRef& t, glm::dvec4 uvs) {
    const dvec2 uv = t.texCoord == 1 ? dvec2(uvs.z, uvs.w) : dvec2(uvs);
    return dvec2(glm::dmat3(t.transform) * glm::dvec3(uv, 1.0));
}

/** The normal texture `map` (`image`) at uv around the interpolated normal N and tangent (xyz,
 *  w the handedness), as common/normal_map.glsl perturbs it on the GPU. */
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

struct Surface {
    std::vector<dvec3> positions, normals;     // world
    std::vector<glm::dvec4> tangents;          // world, where a normal map needs them
    std::vector<glm::dvec4> uv;                // TEXCOORD_0 in xy, TEXCOORD_1 in zw
    const scene::Image* normalImage = nullptr; // the material's normal texture, if it has one
    std::vector<std::uint32_t> indices;
    bool glass = true;
    int solid = 0;                             // the character: one closed solid (media rule)
    const scene::Model* model = nullptr;       // whose material and textures
    const scene::Material* material = nullptr; // opaque surfaces
    Optics optics;                             // glass surfaces
};

struct Hit {
    bool hit = false, ground = false;
    double t = 1e300;
    dvec3 point, shadingNormal;
    dvec3 geometricNormal; // from the winding (glTF: counter-clockwise is outside)
    glm::dvec4 uv{0.0};    // TEXCOORD_0 in xy, TEXCOORD_1 in zw
    const Surface* surface = nullptr;
};

double fresnelEntry(Settings::Fresnel mode, double cosI, double eta) {
    if (mode == Settings::Fresnel::Off)
        return 0.0;
    if (mode == Settings::Fresnel::Schlick) {
        const double f0 = ((1 - eta) / (1 + eta)) * ((1 - eta) / (1 + eta));
        return f0 + (1 - f0) * std::pow(1 - std::clamp(cosI, 0.0, 1.0), 5.0);
    }
    const double sin2T = eta * eta * (1 - cosI * cosI);
    if (sin2T >= 1)
        return 1.0;
    const double cosT = std::sqrt(1 - sin2T);
    const double rs = (eta * cosI - cosT) / (eta * cosI + cosT),
                 rp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

bool refractRay(const dvec3& i, const dvec3& n, double eta, dvec3& t) {
    const double cosI = -glm::dot(i, n), k = 1 - eta * eta * (1 - cosI * cosI);
    if (k < 0)
        return false;
    t = glm::normalize(eta * i + (eta * cosI - std::sqrt(k)) * n);
    return true;
}

/** Small deterministic random numbers (PCG hash) per pixel and sample. */
double random01(std::uint32_t& state) {
    state = state * 747796405u + 2891336453u;
    std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return double((word >> 22u) ^ word) / 4294967296.0;
}

/** The media a path is in (ARCHITECTURE.md, "How a ray walks the layers"): a stack of the
 *  glass surfaces it entered through. Crossing a surface against its outward (winding) normal
 *  enters it; crossing one along it leaves the most recent entry of that surface's solid (its
 *  character), so the pieces of one character (a mesh split by material, interpenetrating
 *  parts) are one solid, and other characters' glass nests inside. The medium is the top
 *  entry's glass, air when empty. */
class Media {
public:
    const Surface* top() const { return mCount ? mEntries[mCount - 1] : nullptr; }
    void enter(const Surface* surface) {
        if (mCount < mEntries.size())
            mEntries[mCount++] = surface;
    }
    void leave(int solid) {
        for (std::size_t i = mCount; i-- > 0;)
            if (mEntries[i]->solid == solid) {
                std::copy(mEntries.begin() + std::ptrdiff_t(i) + 1,
                          mEntries.begin() + std::ptrdiff_t(mCount),
                          mEntries.begin() + std::ptrdiff_t(i));
                --mCount;
                return;
            }
    }

private:
    std::array<const Surface*, 16> mEntries{};
    std::size_t mCount = 0;
};

/** Interfaces into glass where a path follows both the reflection and the refraction. */
constexpr int kSplits = 3;

class Tracer {
public:
    Tracer(const std::vector<Surface>& surfaces, const EnvironmentSampler& env,
           const render::GroundPlane* ground, const ReferenceOptions& options,
           Settings::Fresnel fresnelMode, double epsilon)
        : mSurfaces(surfaces), mEnv(env), mGround(ground), mOptions(options), mFresnel(fresnelMode),
          mEpsilon(epsilon), mDevice(rtcNewDevice(nullptr)), mScene(rtcNewScene(mDevice)) {
        for (const Surface& s : surfaces) {
            RTCGeometry g = rtcNewGeometry(mDevice, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* v = static_cast<float*>(
                rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), s.positions.size()));
            for (std::size_t i = 0; i < s.positions.size(); ++i)
                for (int c = 0; c < 3; ++c)
                    v[i * 3 + std::size_t(c)] = float(s.positions[i][c]);
            auto* idx = static_cast<std::uint32_t*>(
                rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(std::uint32_t), s.indices.size() / 3));
            std::copy(s.indices.begin(), s.indices.end(), idx);
            rtcCommitGeometry(g);
            rtcAttachGeometry(mScene, g);
            rtcReleaseGeometry(g);
        }
        rtcCommitScene(mScene);
    }
    ~Tracer() {
        rtcReleaseScene(mScene);
        rtcReleaseDevice(mDevice);
    }
    Tracer(const Tracer&) = delete;
    Tracer& operator=(const Tracer&) = delete;

    /** Nearest surface along the ray: a triangle of the scene or the ground square. */
    Hit intersect(const dvec3& origin, const dvec3& dir) const {
        Hit h;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        rh.ray.org_x = float(origin.x);
        rh.ray.org_y = float(origin.y);
        rh.ray.org_z = float(origin.z);
        rh.ray.dir_x = float(dir.x);
        rh.ray.dir_y = float(dir.y);
        rh.ray.dir_z = float(dir.z);
        rh.ray.tnear = float(mEpsilon);
        rh.ray.tfar = 1e30f;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(mScene, &context, &rh);
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            const Surface& s = mSurfaces[rh.hit.geomID];
            const std::uint32_t* tri = &s.indices[std::size_t(rh.hit.primID) * 3];
            const double u = rh.hit.u, v = rh.hit.v, w = 1 - u - v;
            h.hit = true;
            h.t = rh.ray.tfar;
            h.surface = &s;
            h.point = w * s.positions[tri[0]] + u * s.positions[tri[1]] + v * s.positions[tri[2]];
            h.shadingNormal = glm::normalize(w * s.normals[tri[0]] + u * s.normals[tri[1]] +
                                             v * s.normals[tri[2]]);
            h.geometricNormal = glm::cross(s.positions[tri[1]] - s.positions[tri[0]],
                                           s.positions[tri[2]] - s.positions[tri[0]]);
            if (!s.uv.empty())
                h.uv = w * s.uv[tri[0]] + u * s.uv[tri[1]] + v * s.uv[tri[2]];
            if (s.normalImage) // every surface the GPU maps, glass (both sides) or opaque
                h.shadingNormal = perturbNormal(
                    s.material->normalTexture, *s.normalImage, h.shadingNormal,
                    w * s.tangents[tri[0]] + u * s.tangents[tri[1]] + v * s.tangents[tri[2]], h.uv);
        }
        if (mGround && std::abs(dir.y) > 1e-12) {
            const double t = (double(mGround->height) - origin.y) / dir.y;
            const dvec3 p = origin + t * dir;
            if (t > mEpsilon && t < h.t && std::abs(p.x - mGround->center.x) <= mGround->halfSize &&
                std::abs(p.z - mGround->center.z) <= mGround->halfSize) {
                h = Hit{};
                h.hit = h.ground = true;
                h.t = t;
                h.point = p;
                h.shadingNormal = dvec3(0, 1, 0);
            }
        }
        return h;
    }

    /** An opaque surface or the ground, lit like render/pbr.frag.glsl or ground.frag.glsl. */
    dvec3 shadeOpaque(const Hit& h, const dvec3& dir) const {
        const dvec3 V = -dir;
        if (h.ground) {
            const double tile = mGround->halfSize / 8.0;
            const double checker =
                std::fmod(std::floor(h.point.x / tile) + std::floor(h.point.z / tile), 2.0);
            const dvec3 base = glm::mix(dvec3(0.30), dvec3(0.42), std::abs(checker));
            return shadeMetallicRoughness(mEnv, base, 0.0, 0.8, dvec3(0, 1, 0), V);
        }
        const scene::Material* m = h.surface->material;
        glm::dvec4 base = m ? glm::dvec4(m->baseColorFactor) : glm::dvec4(1.0);
        double metallic = m ? m->metallicFactor : 1.0, roughness = m ? m->roughnessFactor : 1.0;
        dvec3 emissive = m ? dvec3(m->emissiveFactor) * double(m->emissiveStrength) : dvec3(0.0);
        // KHR_materials_specular: as MaterialTextures::bind and render/pbr.frag.glsl
        double specularWeight = m && m->hasSpecular ? m->specularFactor : 1.0;
        dvec3 specularColor = m && m->hasSpecular ? dvec3(m->specularColorFactor) : dvec3(1.0);
        if (const scene::Model* model = h.surface->model; m && model) {
            auto image = [&](const scene::TextureRef& t) { return textureImage(*model, t); };
            auto uv = [&](const scene::TextureRef& t) { return textureUv(t, h.uv); };
            if (const auto* img = image(m->baseColorTexture))
                base *= sampleImage(*img, uv(m->baseColorTexture), true);
            if (m->unlit) // KHR_materials_unlit
                return dvec3(base);
            if (const auto* img = image(m->metallicRoughnessTexture)) {
                const glm::dvec4 mr = sampleImage(*img, uv(m->metallicRoughnessTexture), false);
                roughness *= mr.g;
                metallic *= mr.b;
            }
            if (const auto* img = image(m->emissiveTexture))
                emissive *= dvec3(sampleImage(*img, uv(m->emissiveTexture), true));
            if (const auto* img = image(m->specularTexture))
                specularWeight *= sampleImage(*img, uv(m->specularTexture), false).a;
            if (const auto* img = image(m->specularColorTexture))
                specularColor *= dvec3(sampleImage(*img, uv(m->specularColorTexture), true));
        }
        dvec3 N = h.shadingNormal;
        if (glm::dot(N, V) < 0)
            N = -N;
        const double f0 = m ? double(m->dielectricF0()) : 0.04;
        return shadeMetallicRoughness(mEnv, dvec3(base), std::clamp(metallic, 0.0, 1.0),
                                      std::clamp(roughness, 0.03, 1.0), N, V, f0 * specularColor,
                                      specularWeight) +
               emissive;
    }

    /** Radiance of channel `c` arriving along a ray from `origin` inside `media`, through
     *  every interface it meets (Media: the rule the GPU's walk follows too): where the ray goes
     *  into glass (from air or from other glass) Fresnel splits it into both branches
     *  (`splits` more times), then chooses one by chance,
     *  a ray leaving glass for air refracts unless totally reflected, Beer-Lambert absorption
     *  in every glass segment. A path ends at an opaque surface, the ground or the environment,
     *  when its throughput is negligible, or after maxBounces interfaces (counted in `trapped`
     *  when still in glass, and black). */
    double follow(dvec3 origin, dvec3 dir, int c, Media media, double weight, int splits,
                  std::uint32_t& rng, std::size_t& trapped) const {
        for (int event = 0;; ++event) {
            const Hit h = intersect(origin, dir);
            const Surface* inside = media.top();
            if (!h.hit) // the environment (or an open mesh's hole)
                return weight * mEnv.radiance(dir, 0.0)[c];
            if (inside)
                weight *= std::exp(-inside->optics.sigma[c] * h.t);
            if (h.ground || !h.surface->glass)
                return weight * shadeOpaque(h, dir)[c];
            if (weight < 1e-4) // negligible: no longer worth following
                return 0.0;
            if (event >= mOptions.maxBounces) {
                if (inside)
                    ++trapped;
                return 0.0;
            }
            Media after = media;
            if (glm::dot(dir, h.geometricNormal) < 0.0)
                after.enter(h.surface);
            else
                after.leave(h.surface->solid);
            const Surface* to = after.top();
            const double n1 = inside ? inside->optics.ior[c] : 1.0;
            const double n2 = to ? to->optics.ior[c] : 1.0;
            origin = h.point;
            if (n1 == n2) { // overlapping glass of one index, or one solid's parts: no interface
                media = after;
                continue;
            }
            dvec3 n = h.shadingNormal;
            if (glm::dot(n, dir) > 0)
                n = -n;
            dvec3 t;
            const bool refracts = refractRay(dir, n, n1 / n2, t);
            const double f =
                refracts && to ? fresnelEntry(mFresnel, -glm::dot(dir, n), n1 / n2) : 0.0;
            if (refracts && f > 0.0 && splits > 0) {
                // Both branches, weighted (the first few times: far less noise than choosing).
                Media entered = after;
                const double reflected = follow(origin, glm::reflect(dir, n), c, media, weight * f,
                                                splits - 1, rng, trapped);
                return reflected + follow(origin, t, c, entered,
                                          weight * (1.0 - f) * to->optics.baseColor[c], splits - 1,
                                          rng, trapped);
            }
            if (!refracts || (f > 0.0 && random01(rng) < f)) {
                dir = glm::reflect(dir, n);
                continue;
            }
            if (!to && mOptions.twoInterfaces)
                return weight * mEnv.radiance(t, 0.0)[c]; // the closed-form model: one exit
            dir = t;
            media = after;
            if (to)
                weight *= to->optics.baseColor[c];
        }
    }

    /** Colour of one camera ray; `glass` reports whether it hit glass first. */
    dvec3 primary(const dvec3& origin, const dvec3& dir, bool& glass, std::uint32_t& rng,
                  std::size_t& trapped) const {
        const Hit h = intersect(origin, dir);
        glass = h.hit && !h.ground && h.surface->glass;
        if (!h.hit)
            return mEnv.radiance(dir, 0.0);
        if (!glass)
            return shadeOpaque(h, dir);
        const Optics& o = h.surface->optics;
        dvec3 n = h.shadingNormal;
        if (glm::dot(n, dir) > 0)
            n = -n;
        const double f = fresnelEntry(mFresnel, -glm::dot(dir, n), 1.0 / o.ior.g);
        const dvec3 reflected = mEnv.radiance(glm::reflect(dir, n), o.roughness);
        Media media;
        media.enter(h.surface);
        dvec3 transmitted;
        for (int c = 0; c < 3; ++c) {
            dvec3 d;
            refractRay(dir, n, 1.0 / o.ior[c], d); // air into glass never reflects totally
            transmitted[c] = follow(h.point, d, c, media, 1.0, kSplits, rng, trapped);
        }
        return double(o.transmission) *
               (f * reflected + (1 - f) * dvec3(o.baseColor) * transmitted);
    }

    /** How many glass surfaces the straight line from `origin` along `dir` crosses before an
     *  opaque surface (what the layered capture stores for the pixel), at most `cap`. */
    int countGlassSurfaces(dvec3 origin, const dvec3& dir, int cap) const {
        int count = 0;
        for (; count < cap; ++count) {
            const Hit h = intersect(origin, dir);
            if (!h.hit || h.ground || !h.surface->glass)
                break;
            origin = h.point;
        }
        return count;
    }

private:
    const std::vector<Surface>& mSurfaces;
    const EnvironmentSampler& mEnv;
    const render::GroundPlane* mGround;
    const ReferenceOptions& mOptions;
    Settings::Fresnel mFresnel;
    double mEpsilon;
    RTCDevice mDevice = nullptr;
    RTCScene mScene = nullptr;
};

} // namespace

core::Result<ReferenceImage>
traceReference(const scene::World& world, double time, const render::Camera& camera,
               const EnvironmentSampler& environment, const render::RenderSettings& settings,
               const render::GroundPlane& ground, const plugin::ParameterSet& glass,
               const ReferenceOptions& options) {
    const Settings decoded = Settings::decode(glass);
    std::vector<Surface> surfaces;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (std::size_t solid = 0; solid < world.characters.size(); ++solid) {
        const scene::Character& character = world.characters[solid];
        const scene::Model& model = *character.model;
        for (const auto& instance : deform::deformCharacter(character, time)) {
            const scene::Mesh& mesh = model.meshes[std::size_t(instance.mesh)];
            for (std::size_t p = 0; p < instance.primitives.size(); ++p) {
                const scene::Primitive& primitive = mesh.primitives[p];
                const auto placed = deform::toWorld(instance.primitives[p], instance.meshToWorld);
                Surface s;
                s.positions = placed.positions;
                s.normals = placed.normals;
                s.indices = primitive.indices;
                if (!primitive.uv0.empty() || !primitive.uv1.empty())
                    for (std::size_t v = 0; v < primitive.vertexCount(); ++v)
                        s.uv.emplace_back(primitive.uvs(v));
                const int material = primitive.materialFor(character.variant);
                s.material = material >= 0 ? &model.materials[std::size_t(material)] : nullptr;
                if (s.material && !s.uv.empty() && !placed.tangents.empty()) {
                    s.normalImage = textureImage(model, s.material->normalTexture);
                    if (s.normalImage)
                        s.tangents = placed.tangents;
                }
                s.model = &model;
                s.glass = decoded.isGlass(model, material, character.glass);
                s.solid = int(solid);
                s.optics = opticsFor(decoded, s.material, character.overrides);
                if (!s.optics.dispersion)
                    s.optics.ior = glm::vec3(s.optics.ior.g);
                for (const auto& v : s.positions) {
                    lo = glm::min(lo, v);
                    hi = glm::max(hi, v);
                }
                surfaces.push_back(std::move(s));
            }
        }
    }
    const double epsilon = surfaces.empty() ? 1e-6 : 1e-5 * glm::length(hi - lo);
    Tracer tracer(surfaces, environment, settings.ground ? &ground : nullptr, options,
                  decoded.fresnel, epsilon);

    ReferenceImage image;
    image.size = settings.size;
    const int w = settings.size.x, h = settings.size.y;
    image.rgba.assign(std::size_t(w) * std::size_t(h) * 4, 0.0f);
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(camera.viewProjection()));
    const int spp = std::max(1, options.samplesPerPixel);
    const int grid = int(std::lround(std::sqrt(double(spp))));
    const bool stratified = grid * grid == spp;
    std::atomic<int> nextRow{0}, rowsDone{0};
    std::atomic<std::size_t> trapped{0};
    constexpr int kCountCap = 64;
    std::vector<std::atomic<std::size_t>> histogram(kCountCap + 1);
    const unsigned threads =
        options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    const bool bar = options.progress && isatty(2);
    auto work = [&] {
        std::size_t localTrapped = 0;
        std::vector<std::size_t> localHistogram(kCountCap + 1, 0);
        for (int row = nextRow++; row < h; row = nextRow++) {
            for (int x = 0; x < w; ++x) {
                dvec3 sum(0.0);
                int glassSamples = 0;
                for (int s = 0; s < spp; ++s) {
                    std::uint32_t rng = std::uint32_t(row) * 73856093u ^
                                        std::uint32_t(x) * 19349663u ^ std::uint32_t(s) * 83492791u;
                    double jx = random01(rng), jy = random01(rng);
                    if (stratified) {
                        jx = (double(s % grid) + jx) / grid;
                        const int stratum =
                            s / grid; // integer division: the sample's row in the grid
                        jy = (stratum + jy) / grid;
                    }
                    const double ndcX = (x + jx) / w * 2.0 - 1.0,
                                 ndcY = (h - 1 - row + jy) / h * 2.0 - 1.0;
                    const glm::dvec4 nearPoint = inverse * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
                    const glm::dvec4 farPoint = inverse * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
                    const dvec3 origin = dvec3(nearPoint) / nearPoint.w;
                    const dvec3 dir = glm::normalize(dvec3(farPoint) / farPoint.w - origin);
                    bool glassHit = false;
                    sum += tracer.primary(origin, dir, glassHit, rng, localTrapped);
                    if (s == 0 && glassHit)
                        ++localHistogram[std::size_t(
                            tracer.countGlassSurfaces(origin, dir, kCountCap))];
                    glassSamples += glassHit ? 1 : 0;
                }
                float* out = &image.rgba[(std::size_t(row) * std::size_t(w) + std::size_t(x)) * 4];
                for (int c = 0; c < 3; ++c)
                    out[c] = float(sum[c] / spp);
                out[3] = float(glassSamples) / float(spp);
            }
            const int done = ++rowsDone;
            if (bar && (done % 8 == 0 || done == h))
                std::fprintf(stderr, "\rreference: [%-40s] %3d%%",
                             std::string(std::size_t(40 * done / h), '#').c_str(), 100 * done / h);
        }
        trapped += localTrapped;
        for (std::size_t i = 0; i < localHistogram.size(); ++i)
            histogram[i] += localHistogram[i];
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back(work);
    for (auto& t : pool)
        t.join();
    if (bar)
        std::fprintf(stderr, "\n");
    image.trappedSamples = trapped.load();
    image.surfaceHistogram.resize(histogram.size());
    for (std::size_t i = 0; i < histogram.size(); ++i)
        image.surfaceHistogram[i] = histogram[i].load();
    while (image.surfaceHistogram.size() > 1 && image.surfaceHistogram.back() == 0)
        image.surfaceHistogram.pop_back();
    return image;
}

std::vector<std::uint8_t> tonemap(const std::vector<float>& rgba, float exposure) {
    std::vector<std::uint8_t> out(rgba.size());
    for (std::size_t i = 0; i < rgba.size(); i += 4) {
        for (int c = 0; c < 3; ++c) {
            double x = std::max(0.0, double(rgba[i + std::size_t(c)]) * exposure);
            x = std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
            x = x < 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
            out[i + std::size_t(c)] = std::uint8_t(std::lround(std::clamp(x, 0.0, 1.0) * 255.0));
        }
        out[i + 3] = 255;
    }
    return out;
}

} // namespace refraction
