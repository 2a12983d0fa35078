// Embree reference tracer: the glass by the optical model's C++ twin (GlassModel.h), the opaque
// scene and the ground shaded like the GPU's opaque pass, the environment sampled like the GPU's.
#include "refraction/ReferenceTracer.h"

#include "PhotonMap.h"
#include "ReferenceScene.h"
#include "model/GlassModel.h"
#include "model/Optics.h"

#include "engine/render/CpuShading.h"
#include "engine/render/Lighting.h"
#include "engine/render/Shadows.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <thread>
#include <unistd.h>

namespace refraction {

using glm::dvec2;
using glm::dvec3;
using glm::dvec4;
using reference::Surface;
using render::cpu::perturbNormal;
using render::cpu::textureImage;

namespace {

struct Hit {
    bool hit = false, ground = false;
    double t = 1e300;
    dvec3 point, shadingNormal;
    dvec3 interpolatedNormal; // before the normal map
    dvec4 tangent{0.0};
    dvec3 geometricNormal; // from the winding (glTF: counter-clockwise is outside)
    glm::dvec4 uv{0.0};    // TEXCOORD_0 in xy, TEXCOORD_1 in zw
    const Surface* surface = nullptr;
};

/** How a reference path is evaluated: sampled (jittered rays, rough surfaces by microfacets,
 *  one branch by chance past the splits: the ground truth) or deterministic (docs/methods.md:
 *  the model the GPU trace runs at one sample a pixel). */
struct Evaluation {
    bool deterministic = false;
    int interfaces = 0, crossings = 0; ///< deterministic: where a path ends (the trace's bounds)
};

/** Which shadows the reference traces: none with RenderSettings::shadows off; the glass's
 *  with the plugin's glass-shadows on. */
struct Shadows {
    bool enabled = true, glass = true;
};

/** work(row, thread) for every row in 0..rows-1, shared over `threads` threads (0..threads-1),
 *  each taking the next row as it finishes one. */
template <class Work> void forEachRow(int rows, unsigned threads, const Work& work) {
    std::atomic<int> next{0};
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (int row = next++; row < rows; row = next++)
                work(row, t);
        });
    for (auto& thread : pool)
        thread.join();
}

class Tracer {
public:
    Tracer(const std::vector<Surface>& surfaces, const EnvironmentSampler& env,
           const render::GroundPlane* ground, const ReferenceOptions& options,
           Settings::Fresnel fresnelMode, double epsilon, std::vector<scene::PlacedLight> lights,
           Evaluation evaluation, const Shadows& shadows)
        : mSurfaces(surfaces), mEnv(env), mLights(std::move(lights)), mGround(ground),
          mOptions(options), mFresnel(fresnelMode), mEpsilon(epsilon), mEvaluation(evaluation),
          mDevice(rtcNewDevice(nullptr)), mScene(rtcNewScene(mDevice)), mShadows(shadows),
          mCasts(shadows.enabled ? render::castingLights(mLights)
                                 : std::vector<bool>(mLights.size(), false)),
          mLighting{mEnv, mLights,
                    [this](std::size_t i, dvec3 P, dvec3 N, dvec3 L) {
                        return lightThrough(i, P, N, L, true);
                    }},
          mGlassLighting{mEnv, mLights, [this](std::size_t i, dvec3 P, dvec3 N, dvec3 L) {
                             return lightThrough(i, P, N, L, false);
                         }} {
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

    /** Nearest surface along the ray: a triangle of the scene or the ground square (with
     *  `glass` false, the nearest that is not glass). */
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
            h.shadingNormal = h.interpolatedNormal = glm::normalize(
                w * s.normals[tri[0]] + u * s.normals[tri[1]] + v * s.normals[tri[2]]);
            h.geometricNormal = glm::cross(s.positions[tri[1]] - s.positions[tri[0]],
                                           s.positions[tri[2]] - s.positions[tri[0]]) *
                                (s.mirrored ? -1.0 : 1.0);
            if (!s.uv.empty())
                h.uv = w * s.uv[tri[0]] + u * s.uv[tri[1]] + v * s.uv[tri[2]];
            if (!s.tangents.empty())
                h.tangent =
                    w * s.tangents[tri[0]] + u * s.tangents[tri[1]] + v * s.tangents[tri[2]];
            if (s.normalImage) // every surface the GPU maps, glass (both sides) or opaque
                h.shadingNormal = perturbNormal(s.material->normalTexture, *s.normalImage,
                                                h.shadingNormal, h.tangent, h.uv);
        }
        if (const double t = groundHit(origin, dir); t > mEpsilon && t < h.t) {
            h = Hit{};
            h.hit = h.ground = true;
            h.t = t;
            h.point = origin + t * dir;
            h.shadingNormal = dvec3(0, 1, 0);
        }
        return h;
    }

    /** Where the ray meets the ground square (t), or -1. */
    double groundHit(const dvec3& origin, const dvec3& dir) const {
        if (!mGround || std::abs(dir.y) <= 1e-12)
            return -1.0;
        const double t = (double(mGround->height) - origin.y) / dir.y;
        const dvec3 p = origin + t * dir;
        return t > 0.0 && std::abs(p.x - mGround->center.x) <= mGround->halfSize &&
                       std::abs(p.z - mGround->center.z) <= mGround->halfSize
                   ? t
                   : -1.0;
    }

    /** An opaque surface or the ground, lit like render/opaque.frag.glsl or ground.frag.glsl. */
    dvec3 shadeOpaque(const Hit& h, const dvec3& dir) const {
        const dvec3 V = -dir;
        const render::cpu::Lighting& lighting = mLighting;
        render::cpu::Surface surface;
        if (h.ground) {
            const double tile = mGround->halfSize / 8.0;
            const double checker =
                std::fmod(std::floor(h.point.x / tile) + std::floor(h.point.z / tile), 2.0);
            surface.baseColor = glm::mix(dvec3(0.30), dvec3(0.42), std::abs(checker));
            surface.metallic = 0.0;
            surface.roughness = 0.8;
            return render::cpu::shadeSurface(surface, lighting, h.point, dvec3(0, 1, 0), V);
        }
        const scene::Material* m = h.surface->material;
        const double side = glm::dot(h.shadingNormal, V) < 0 ? -1.0 : 1.0; // toward the viewer
        const render::cpu::Point point{h.point, side * h.interpolatedNormal, side * h.shadingNormal,
                                       h.tangent, h.uv};
        dvec3 emissive(0.0);
        if (m && h.surface->model)
            surface = render::cpu::readSurface(*h.surface->model, *m, point, emissive);
        if (m && m->unlit) // KHR_materials_unlit
            return surface.baseColor;
        return render::cpu::shadeSurface(surface, lighting, h.point, point.normal, V) + emissive;
    }

    /** The glass surface at a hit: its optics' factors times its textures at the hit's uv
     *  (level 0): base colour always, transmission, roughness and metallic where the material
     *  is glass by its own transmission (forced glass is clear). */
    model::GlassSurface glassSurface(const Hit& h) const {
        const Surface& s = *h.surface;
        model::GlassSurface g;
        g.baseColor = dvec3(s.optics.baseColor);
        g.transmission = s.optics.transmission;
        g.roughness = s.optics.roughness;
        g.metallic = s.optics.metallic;
        if (!s.material || !s.model)
            return g;
        auto read = [&](const scene::TextureRef& t, bool srgb) {
            const scene::Image* image = textureImage(*s.model, t);
            return image ? render::cpu::sampleImage(*image, render::cpu::textureUv(t, h.uv), srgb)
                         : dvec4(1.0);
        };
        g.baseColor *= dvec3(read(s.material->baseColorTexture, true));
        if (s.authored) {
            g.transmission *= read(s.material->transmissionTexture, false).r;
            const dvec4 mr = read(s.material->metallicRoughnessTexture, false);
            g.roughness *= mr.g;
            g.metallic *= mr.b;
        }
        return g;
    }

    /** The environment or the ground straight along a ray (a path at the deterministic
     *  evaluation's end, as the GPU trace's lookup). */
    double beyond(const dvec3& origin, const dvec3& dir, double roughness, int c) const {
        const double t = groundHit(origin, dir);
        if (t > mEpsilon) {
            Hit h;
            h.hit = h.ground = true;
            h.point = origin + t * dir;
            return shadeOpaque(h, dir)[c];
        }
        return mEnv.radiance(dir, roughness)[c];
    }

    /** The roughness a path's lookup blurs by: its roughest interface where rough surfaces
     *  are not sampled. */
    double lookupRoughness(const model::Path& path) const {
        return mEvaluation.deterministic ? path.roughness : 0.0;
    }

    /** A facet normal for a crossing of surface `s` about the (facing) shading normal `n`: a
     *  sampled microfacet's where the surface is rough and paths are sampled, else n. */
    dvec3 facet(const model::GlassSurface& s, const dvec3& n, const dvec3& dir,
                std::uint32_t& rng) const {
        if (mEvaluation.deterministic || s.roughness <= model::kSmooth)
            return n;
        const double u1 = model::random01(rng), u2 = model::random01(rng);
        return model::sampleMicrofacet(n, s.roughness, -dir, u1, u2);
    }

    /** Radiance of channel `c` arriving along `path` from its origin, through every surface it
     *  meets (model::crossInterface): Beer-Lambert in each glass segment, the reflections of
     *  interfaces into glass followed as branches of their own (the model's split rule where
     *  deterministic, model::kSampledSplitDepth where sampled), then
     *  looked up along their direction (deterministic) or chosen by Fresnel (sampled). A path
     *  ends at an opaque surface, the ground or the environment, when its throughput is
     *  negligible, or: deterministic, after the trace's interfaces (seeing what lies along it);
     *  sampled, after maxBounces (black, counted in `trapped` when still in glass). */
    double follow(model::Path path, int c, std::uint32_t& rng, std::size_t& trapped) const {
        double light = 0.0;
        for (;;) {
            if (mEvaluation.deterministic && (path.interfaces >= mEvaluation.interfaces ||
                                              path.crossings >= mEvaluation.crossings))
                return light + path.weight * beyond(path.origin, path.dir, path.roughness, c);
            const Hit h = intersect(path.origin, path.dir);
            const bool inGlass = path.media.top() != nullptr;
            if (!h.hit) // the environment (or an open mesh's hole)
                return light + path.weight * mEnv.radiance(path.dir, lookupRoughness(path))[c];
            if (inGlass)
                path.weight *= std::exp(-path.sigma * h.t);
            if (h.ground || !h.surface->glass)
                return light + path.weight * shadeOpaque(h, path.dir)[c];
            if (path.weight < 1e-4) // negligible: no longer worth following
                return light;
            if (path.crossings >= mOptions.maxBounces) {
                if (inGlass)
                    ++trapped;
                return light;
            }
            const model::SurfaceMet met{&h.surface->optics, h.surface->solid, glassSurface(h),
                                        glm::dot(path.dir, h.geometricNormal) < 0.0};
            path.origin = h.point;
            const dvec3 n =
                glm::dot(h.shadingNormal, path.dir) > 0 ? -h.shadingNormal : h.shadingNormal;
            const dvec3 m = facet(met.surface, n, path.dir, rng), incoming = path.dir;
            const model::Path before = path;
            double reflected = 0.0;
            const model::Crossed crossed =
                model::crossInterface(path, met, m, c, mFresnel, reflected);
            if (crossed == model::Crossed::Passed)
                continue;
            const bool rough = m != n;
            if (rough) // the facet's share of the light, the way it went
                path.weight *= model::microfacetWeight(path.dir, m, n, met.surface.roughness,
                                                       crossed == model::Crossed::Refracted);
            if (crossed == model::Crossed::Reflected)
                continue;
            if (!path.media.top() && mOptions.twoInterfaces)
                return light + path.weight * mEnv.radiance(path.dir, 0.0)[c]; // one exit
            if (reflected <= 0.0)
                continue;
            model::Path mirror = before;
            mirror.dir = glm::reflect(incoming, glm::dot(m, incoming) > 0 ? -m : m);
            mirror.weight =
                reflected *
                (rough ? model::microfacetWeight(mirror.dir, m, n, met.surface.roughness, false)
                       : 1.0);
            mirror.interfaces = path.interfaces;
            mirror.crossings = path.crossings;
            mirror.roughness = std::max(before.roughness, met.surface.roughness);
            const bool split = mEvaluation.deterministic ? path.splits < model::kSplitDepth &&
                                                               mirror.weight >= model::kSplitWeight
                                                         : path.splits < model::kSampledSplitDepth;
            if (split) {
                ++path.splits;
                mirror.splits = path.splits;
                light += follow(mirror, c, rng, trapped);
            } else if (mEvaluation.deterministic) {
                light += mirror.weight * mEnv.radiance(mirror.dir, mirror.roughness)[c];
            } else { // one branch by chance, as likely as the share it carries
                const double p = reflected / before.weight;
                if (model::random01(rng) < p) {
                    mirror.weight /= p;
                    path = mirror;
                } else {
                    path.weight /= 1.0 - p;
                }
            }
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
        const model::GlassSurface s = glassSurface(h);
        dvec3 n = h.shadingNormal;
        if (glm::dot(n, dir) > 0)
            n = -n;
        const double cosI = -glm::dot(dir, n);
        dvec3 F;
        for (int c = 0; c < 3; ++c)
            F[c] = model::reflectance(mFresnel, o, s, cosI, 1.0 / o.ior.g, c);
        const dvec3 reflected = mEnv.radiance(glm::reflect(dir, n), s.roughness);
        dvec3 transmitted;
        for (int c = 0; c < 3; ++c) {
            model::Path path;
            path.origin = h.point;
            path.media.enter(&o, h.surface->solid);
            path.ior = o.ior[c];
            path.sigma = o.sigma[c];
            path.roughness = s.roughness;
            const dvec3 m = facet(s, n, dir, rng);
            refractOrReflect(dir, m, 1.0 / o.ior[c], path.dir);
            if (m != n)
                path.weight = model::microfacetWeight(path.dir, m, n, s.roughness, true);
            transmitted[c] = follow(path, c, rng, trapped);
        }
        const dvec3 tint = s.baseColor * (1.0 - s.metallic);
        return glassColor(h, o, s, n, -dir, F * reflected + (1.0 - F) * tint * transmitted);
    }

    /** Refracts about m; reflects where it cannot (air into glass reflects totally only about a
     *  microfacet tilted far from the ray). */
    static void refractOrReflect(const dvec3& dir, const dvec3& m, double eta, dvec3& out) {
        if (!model::refract(dir, m, eta, out))
            out = glm::reflect(dir, m);
    }

    /** What glass_surface.glsl's glassColor adds at the entry (normal n and view V facing each
     *  other) to `glass`, its reflection and transmission: the lights' highlights, the opaque
     *  term where transmission is partial, the clear coat and sheen, emission. */
    dvec3 glassColor(const Hit& h, const Optics& o, const model::GlassSurface& s, dvec3 n, dvec3 V,
                     dvec3 glass) const {
        const render::cpu::Lighting& lighting = mGlassLighting;
        const double NoV = std::clamp(glm::dot(n, V), 1e-4, 1.0);
        const double alpha = std::pow(std::max(s.roughness, 0.03), 2.0);
        for (std::size_t i = 0; i < mLights.size(); ++i) {
            dvec3 L;
            const dvec3 arriving = render::cpu::lightArriving(lighting, i, h.point, n, L);
            const dvec3 H = glm::normalize(L + V);
            const double NoL = glm::dot(n, L), VoH = std::max(glm::dot(V, H), 0.0);
            if (NoL > 0.0)
                for (int c = 0; c < 3; ++c)
                    glass[c] +=
                        arriving[c] * NoL *
                        model::reflectance(mFresnel, o, s, VoH, 1.0 / o.ior.g, c) *
                        render::cpu::ggxLobe(NoL, NoV, std::max(glm::dot(n, H), 0.0), alpha);
        }
        render::cpu::Surface surface;
        surface.baseColor = s.baseColor;
        surface.metallic = s.metallic;
        surface.roughness = std::max(s.roughness, 0.03);
        dvec3 color = glass;
        if (s.transmission < 1.0)
            color = glm::mix(render::cpu::shadeSurface(surface, lighting, h.point, n, V), glass,
                             s.transmission);
        surface.clearcoat = o.clearcoat;
        surface.clearcoatRoughness = o.clearcoatRoughness;
        surface.clearcoatNormal = n;
        surface.sheenColor = dvec3(o.sheenColor);
        surface.sheenRoughness = o.sheenRoughness;
        const scene::Material* m = h.surface->material;
        const dvec3 emissive =
            m ? dvec3(m->emissiveFactor) * double(m->emissiveStrength) : dvec3(0.0);
        return render::cpu::layersOver(color, surface, lighting, h.point, n, V) + emissive;
    }

    /** What reaches P (normal N) of light `i` toward L, as a share of the light unblocked, as
     *  the GPU's shadow maps hold it (docs/materials.md, "Shadows" and "Caustics"): nothing
     *  past an opaque surface (the ground casts none). With the caustics, a `receiver` (an
     *  opaque surface or the ground) gets the light no glass stands in front of, plus the
     *  caustics' photons' irradiance around it over what the light would bring unblocked;
     *  else (the glass's own highlights, or without caustics) light through glass goes
     *  straight: at each crossing 1 - F at the light's angle (the entering reflectance),
     *  entering its tint and transmission too, and Beer-Lambert over the length inside. */
    dvec3 lightThrough(std::size_t i, dvec3 P, dvec3 N, dvec3 L, bool receiver) const {
        if (!mCasts[i])
            return dvec3(1.0);
        const bool focused = receiver && !mCaustics.empty();
        const scene::PlacedLight& light = mLights[i];
        const bool directional = light.light.type == scene::Light::Type::Directional;
        double remaining = directional ? 1e300 : glm::distance(dvec3(light.position), P);
        dvec3 origin = P + (glm::dot(N, L) < 0.0 ? -N : N) * (4.0 * mEpsilon);
        dvec3 depth(0.0);       // optical depth, -ln of what passes
        double travelled = 0.0; // from P toward the light
        bool behindGlass = false;
        for (int crossing = 0; crossing < 1024; ++crossing) {
            const Hit h = intersect(origin, L);
            if (!h.hit || h.t >= remaining)
                break;
            travelled += h.t;
            if (!h.ground) {
                if (!h.surface->glass || !mShadows.glass)
                    return dvec3(0.0);
                behindGlass = true;
                const Optics& o = h.surface->optics;
                const model::GlassSurface s = glassSurface(h);
                const bool facesLight = glm::dot(h.geometricNormal, L) > 0.0;
                const double cosI =
                    std::clamp(std::abs(glm::dot(glm::normalize(h.shadingNormal), L)), 1e-4, 1.0);
                // Distance from the light, up to a constant that cancels between a solid's two
                // crossings: minus the way travelled toward it.
                const double fromLight = -travelled;
                for (int c = 0; c < 3; ++c) {
                    double through =
                        1.0 - model::reflectance(mFresnel, o, s, cosI, 1.0 / o.ior.g, c);
                    if (facesLight)
                        through *= s.baseColor[c] * (1.0 - s.metallic) * s.transmission;
                    depth[c] += -std::log(std::max(through, 1e-6)) +
                                (facesLight ? -1.0 : 1.0) * o.sigma[c] * fromLight;
                }
            }
            origin = h.point;
            remaining -= h.t;
        }
        if (!focused)
            return glm::exp(-glm::max(depth, dvec3(0.0)));
        // The light unblocked per unit area of the receiver, its intensity as 1.
        double unblocked = std::max(glm::dot(N, L), 1e-3);
        if (light.light.type != scene::Light::Type::Directional) {
            unblocked /=
                std::max(glm::dot(dvec3(light.position) - P, dvec3(light.position) - P), 1e-8);
            if (light.light.type == scene::Light::Type::Spot)
                unblocked *= render::cpu::spotFalloff(light, L);
        }
        const dvec3 focusedLight =
            unblocked > 0.0 ? mCaustics[i].irradiance(P) / unblocked : dvec3(0.0);
        return (behindGlass ? 0.0 : 1.0) + focusedLight;
    }

    /** The caustics' photons of every casting light (docs/materials.md, "Caustics"): `count`
     *  a light, sent over the cone (a directional light: the disc) that holds the glass's
     *  bounding sphere, stratified; each that meets glass first follows its refracted path
     *  (model::crossInterface, the reflected share dropped, total internal reflection
     *  followed, Beer-Lambert between surfaces), a path a channel, and lands on the first
     *  opaque surface or the ground it meets in air after the glass; gathered within
     *  `radius` (0: a twentieth of the glass's bounding radius). */
    void traceCaustics(int count, double radius, unsigned threads) {
        const auto [lo, hi] = reference::surfaceBounds(mSurfaces, true);
        if (lo.x > hi.x)
            return;
        const dvec3 centre = 0.5 * (lo + hi);
        const double bound = 0.5 * glm::length(hi - lo);
        if (radius <= 0.0)
            radius = bound / 20.0;
        mCaustics.assign(mLights.size(), PhotonMap{});
        const int side = std::max(1, int(std::ceil(std::sqrt(double(count)))));
        for (std::size_t i = 0; i < mLights.size(); ++i) {
            if (!mCasts[i])
                continue;
            std::vector<std::vector<Photon>> landed(threads);
            forEachRow(side, threads, [&](int row, unsigned t) {
                for (int column = 0; column < side; ++column)
                    emitPhoton(i, centre, bound, (column + 0.5) / side, (row + 0.5) / side,
                               1.0 / (double(side) * side), landed[t]);
            });
            std::vector<Photon> all;
            for (auto& part : landed)
                all.insert(all.end(), part.begin(), part.end());
            mCaustics[i] = PhotonMap(std::move(all), radius);
        }
    }

    /** One photon of light `i` toward the glass's bounding sphere (centre, bound) at the
     *  stratum (u, v), a `share` of its photons: its landings into `landed`. */
    void emitPhoton(std::size_t i, const dvec3& centre, double bound, double u, double v,
                    double share, std::vector<Photon>& landed) const {
        const scene::PlacedLight& light = mLights[i];
        const double phi = 2.0 * std::numbers::pi * v;
        dvec3 origin, dir, flux;
        if (light.light.type == scene::Light::Type::Directional) {
            dir = glm::normalize(dvec3(light.direction));
            const auto [a, b] = model::tangentFrame(dir);
            const double r = bound * std::sqrt(u);
            origin = centre - 2.0 * bound * dir + r * (std::cos(phi) * a + std::sin(phi) * b);
            flux = dvec3(std::numbers::pi * bound * bound * share);
        } else {
            origin = dvec3(light.position);
            const dvec3 axis = centre - origin;
            const double d = glm::length(axis);
            const double cosMax = d > bound ? std::sqrt(1.0 - (bound / d) * (bound / d)) : -1.0;
            const double cosTheta = 1.0 - u * (1.0 - cosMax);
            const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
            const dvec3 w = d > 0.0 ? axis / d : dvec3(0, -1, 0);
            const auto [a, b] = model::tangentFrame(w);
            dir = cosTheta * w + sinTheta * (std::cos(phi) * a + std::sin(phi) * b);
            double intensity = 2.0 * std::numbers::pi * (1.0 - cosMax) * share;
            if (light.light.type == scene::Light::Type::Spot)
                intensity *= render::cpu::spotFalloff(light, -dir);
            flux = dvec3(intensity);
        }
        if (flux.x <= 0.0)
            return;
        const Hit first = intersect(origin, dir);
        if (!first.hit || first.ground || !first.surface->glass)
            return; // straight light, or stopped
        for (int c = 0; c < 3; ++c) {
            model::Path path;
            path.origin = origin;
            path.dir = dir;
            path.weight = flux[c];
            for (int k = 0; k <= model::kMaxPhotonCrossings; ++k) {
                const Hit h = intersect(path.origin, path.dir);
                const bool inGlass = path.media.top() != nullptr;
                if (!h.hit)
                    break;
                if (inGlass)
                    path.weight *= std::exp(-path.sigma * h.t);
                if (h.ground || !h.surface->glass) {
                    if (!inGlass && path.crossings > 0) {
                        Photon p{h.point, dvec3(0.0)};
                        p.light[c] = path.weight;
                        landed.push_back(p);
                    }
                    break;
                }
                if (k == model::kMaxPhotonCrossings || path.weight < 1e-9)
                    break;
                const model::SurfaceMet met{&h.surface->optics, h.surface->solid, glassSurface(h),
                                            glm::dot(path.dir, h.geometricNormal) < 0.0};
                path.origin = h.point;
                const dvec3 n =
                    glm::dot(h.shadingNormal, path.dir) > 0 ? -h.shadingNormal : h.shadingNormal;
                double reflected = 0.0;
                model::crossInterface(path, met, n, c, mFresnel, reflected);
            }
        }
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
    std::vector<scene::PlacedLight> mLights; // world space
    const render::GroundPlane* mGround;
    const ReferenceOptions& mOptions;
    Settings::Fresnel mFresnel;
    double mEpsilon;
    Evaluation mEvaluation;
    RTCDevice mDevice = nullptr;
    RTCScene mScene = nullptr;
    Shadows mShadows;
    std::vector<bool> mCasts; ///< per light: it casts (render::castingLights)
    /** Per light, its caustics' photons (traceCaustics; empty: the light goes straight). */
    std::vector<PhotonMap> mCaustics;
    /** The lights with lightThrough as their visibility: for the receivers, and for the
     *  glass's own shading (straight through the glass). */
    render::cpu::Lighting mLighting, mGlassLighting;
};

/** The camera's rays through a pixel: `spp` samples, jittered (stratified where `spp` is a
 *  square) or through its centre. */
struct PixelRays {
    glm::dmat4 inverseViewProjection;
    glm::ivec2 size;
    int spp = 1, grid = 1;
    bool centres = false, stratified = false;

    PixelRays(const render::Camera& camera, glm::ivec2 viewport, const ReferenceOptions& options)
        : inverseViewProjection(glm::inverse(glm::dmat4(camera.viewProjection()))), size(viewport) {
        centres = options.pixelCentres || options.deterministic;
        spp = centres ? 1 : std::max(1, options.samplesPerPixel);
        grid = int(std::lround(std::sqrt(double(spp))));
        stratified = grid * grid == spp;
    }

    /** Sample `s` of pixel (x, row), row 0 at the top; `rng` seeded for it. */
    void ray(int x, int row, int s, std::uint32_t& rng, dvec3& origin, dvec3& dir) const {
        rng = std::uint32_t(row) * 73856093u ^ std::uint32_t(x) * 19349663u ^
              std::uint32_t(s) * 83492791u;
        double jx = model::random01(rng), jy = model::random01(rng);
        if (centres) {
            jx = jy = 0.5;
        } else if (stratified) {
            jx = (double(s % grid) + jx) / grid;
            jy = (double(s / grid) + jy) / grid; // the sample's row in the grid
        }
        const double ndcX = (x + jx) / size.x * 2.0 - 1.0,
                     ndcY = (size.y - 1 - row + jy) / size.y * 2.0 - 1.0;
        const glm::dvec4 nearPoint = inverseViewProjection * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
        const glm::dvec4 farPoint = inverseViewProjection * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
        origin = dvec3(nearPoint) / nearPoint.w;
        dir = glm::normalize(dvec3(farPoint) / farPoint.w - origin);
    }
};

} // namespace

core::Result<ReferenceImage>
traceReference(const scene::World& world, double time, const render::Camera& camera,
               const EnvironmentSampler& environment, const render::RenderSettings& settings,
               const render::GroundPlane& ground, const plugin::ParameterSet& glass,
               const ReferenceOptions& options) {
    const Settings decoded = Settings::decode(glass);
    auto built = reference::worldSurfaces(world, time, decoded, options.subdivision);
    if (!built)
        return built.error();
    const std::vector<Surface>& surfaces = *built;
    const double epsilon = reference::sceneEpsilon(surfaces);
    const Evaluation evaluation{options.deterministic, decoded.interfaces - 1,
                                2 * decoded.interfaces};
    Tracer tracer(surfaces, environment, settings.ground ? &ground : nullptr, options,
                  decoded.fresnel, epsilon, render::worldLights(world, time), evaluation,
                  Shadows{settings.shadows, decoded.glassShadows});
    const unsigned threads =
        options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    if (settings.shadows && decoded.focusesCaustics())
        tracer.traceCaustics(options.photons, options.causticRadius, threads);

    ReferenceImage image;
    image.size = settings.size;
    const int w = settings.size.x, h = settings.size.y;
    image.rgba.assign(std::size_t(w) * std::size_t(h) * 4, 0.0f);
    const PixelRays rays(camera, settings.size, options);
    const int spp = rays.spp;
    std::atomic<int> rowsDone{0};
    constexpr int kCountCap = 64;
    // Per thread: the samples trapped, and the histogram of glass surfaces.
    std::vector<std::size_t> trapped(threads, 0);
    std::vector<std::vector<std::size_t>> histograms(threads,
                                                     std::vector<std::size_t>(kCountCap + 1, 0));
    const bool bar = options.progress && isatty(2);
    forEachRow(h, threads, [&](int row, unsigned t) {
        for (int x = 0; x < w; ++x) {
            dvec3 sum(0.0);
            int glassSamples = 0;
            for (int s = 0; s < spp; ++s) {
                std::uint32_t rng = 0;
                dvec3 origin, dir;
                rays.ray(x, row, s, rng, origin, dir);
                bool glassHit = false;
                sum += tracer.primary(origin, dir, glassHit, rng, trapped[t]);
                if (s == 0 && glassHit)
                    ++histograms[t][std::size_t(tracer.countGlassSurfaces(origin, dir, kCountCap))];
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
    });
    if (bar)
        std::fprintf(stderr, "\n");
    image.trappedSamples = 0;
    image.surfaceHistogram.assign(kCountCap + 1, 0);
    for (unsigned t = 0; t < threads; ++t) {
        image.trappedSamples += trapped[t];
        for (std::size_t i = 0; i < image.surfaceHistogram.size(); ++i)
            image.surfaceHistogram[i] += histograms[t][i];
    }
    while (image.surfaceHistogram.size() > 1 && image.surfaceHistogram.back() == 0)
        image.surfaceHistogram.pop_back();
    return image;
}

} // namespace refraction
