// Embree reference tracer: glass with real TIR, the opaque scene and the ground shaded like the
// GPU's opaque pass, the environment sampled like the GPU's.
#include "refraction/ReferenceTracer.h"

#include "Optics.h"

#include "engine/deform/CpuDeformer.h"
#include "engine/render/CpuShading.h"
#include "engine/render/Lighting.h"

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
using glm::dvec4;
using render::cpu::perturbNormal;
using render::cpu::textureImage;

namespace {

struct Surface {
    std::vector<dvec3> positions, normals;     // world
    std::vector<glm::dvec4> tangents;          // world, where a map or anisotropy needs them
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
    dvec3 interpolatedNormal; // before the normal map
    dvec4 tangent{0.0};
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
           Settings::Fresnel fresnelMode, double epsilon, std::vector<scene::PlacedLight> lights)
        : mSurfaces(surfaces), mEnv(env), mLights(std::move(lights)), mGround(ground),
          mOptions(options), mFresnel(fresnelMode), mEpsilon(epsilon),
          mDevice(rtcNewDevice(nullptr)), mScene(rtcNewScene(mDevice)) {
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
            h.shadingNormal = h.interpolatedNormal = glm::normalize(
                w * s.normals[tri[0]] + u * s.normals[tri[1]] + v * s.normals[tri[2]]);
            h.geometricNormal = glm::cross(s.positions[tri[1]] - s.positions[tri[0]],
                                           s.positions[tri[2]] - s.positions[tri[0]]);
            if (!s.uv.empty())
                h.uv = w * s.uv[tri[0]] + u * s.uv[tri[1]] + v * s.uv[tri[2]];
            if (!s.tangents.empty())
                h.tangent =
                    w * s.tangents[tri[0]] + u * s.tangents[tri[1]] + v * s.tangents[tri[2]];
            if (s.normalImage) // every surface the GPU maps, glass (both sides) or opaque
                h.shadingNormal = perturbNormal(s.material->normalTexture, *s.normalImage,
                                                h.shadingNormal, h.tangent, h.uv);
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
        const render::cpu::Lighting lighting{mEnv, mLights};
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

    /** The reflectance of glass `o` from air at cosI in channel `c`, as glass_surface.glsl's
     *  glassReflectance: the Fresnel mode's, coloured and weighted by KHR_materials_specular,
     *  through the iridescent film. */
    double glassReflectance(const Optics& o, double cosI, int c) const {
        const double eta = 1.0 / o.ior.g;
        double F = fresnelEntry(mFresnel, cosI, eta);
        if (o.specularColor != glm::vec3(1.0f) || o.specularWeight != 1.0f) {
            const double f0 = fresnelEntry(mFresnel, 1.0, eta);
            const double coloured = std::min(f0 * o.specularColor[c], 1.0);
            F = o.specularWeight *
                (coloured + (1.0 - coloured) * (f0 < 1.0 ? (F - f0) / (1.0 - f0) : 1.0));
        }
        if (o.iridescence > 0.0f && mFresnel != Settings::Fresnel::Off)
            F = glm::mix(F,
                         render::cpu::thinFilmReflectance(
                             cosI, o.iridescenceIor, o.iridescenceThickness, dvec3(o.ior.g))[c],
                         double(o.iridescence));
        return F;
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
            const double f = !refracts || !to ? 0.0
                             : inside         ? fresnelEntry(mFresnel, -glm::dot(dir, n), n1 / n2)
                                              : glassReflectance(to->optics, -glm::dot(dir, n), c);
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
        const double cosI = -glm::dot(dir, n);
        const dvec3 F(glassReflectance(o, cosI, 0), glassReflectance(o, cosI, 1),
                      glassReflectance(o, cosI, 2));
        const dvec3 reflected = mEnv.radiance(glm::reflect(dir, n), o.roughness);
        Media media;
        media.enter(h.surface);
        dvec3 transmitted;
        for (int c = 0; c < 3; ++c) {
            dvec3 d;
            refractRay(dir, n, 1.0 / o.ior[c], d); // air into glass never reflects totally
            transmitted[c] = follow(h.point, d, c, media, 1.0, kSplits, rng, trapped);
        }
        return glassColor(h, o, n, -dir,
                          F * reflected + (1.0 - F) * dvec3(o.baseColor) * transmitted);
    }

    /** What glass_surface.glsl's glassColor adds at the entry (normal n and view V facing each
     *  other) to `glass`, its reflection and transmission: the lights' highlights, the opaque
     *  term where transmission is partial, the clear coat and sheen, emission. */
    dvec3 glassColor(const Hit& h, const Optics& o, dvec3 n, dvec3 V, dvec3 glass) const {
        const render::cpu::Lighting lighting{mEnv, mLights};
        const double NoV = std::clamp(glm::dot(n, V), 1e-4, 1.0);
        const double alpha = std::pow(std::max(double(o.roughness), 0.03), 2.0);
        for (const scene::PlacedLight& light : mLights) {
            dvec3 L;
            const dvec3 arriving = render::cpu::lightArriving(light, h.point, L);
            const dvec3 H = glm::normalize(L + V);
            const double NoL = glm::dot(n, L), VoH = std::max(glm::dot(V, H), 0.0);
            if (NoL > 0.0)
                glass += arriving * NoL *
                         dvec3(glassReflectance(o, VoH, 0), glassReflectance(o, VoH, 1),
                               glassReflectance(o, VoH, 2)) *
                         render::cpu::ggxLobe(NoL, NoV, std::max(glm::dot(n, H), 0.0), alpha);
        }
        render::cpu::Surface surface;
        surface.baseColor = dvec3(o.baseColor);
        surface.metallic = o.metallic;
        surface.roughness = std::max(double(o.roughness), 0.03);
        dvec3 color = glass;
        if (o.transmission < 1.0f)
            color = glm::mix(render::cpu::shadeSurface(surface, lighting, h.point, n, V), glass,
                             double(o.transmission));
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
                    if (s.normalImage || s.material->hasAnisotropy ||
                        s.material->clearcoatNormalTexture.present())
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
                  decoded.fresnel, epsilon, render::worldLights(world, time));

    ReferenceImage image;
    image.size = settings.size;
    const int w = settings.size.x, h = settings.size.y;
    image.rgba.assign(std::size_t(w) * std::size_t(h) * 4, 0.0f);
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(camera.viewProjection()));
    const int spp = options.pixelCentres ? 1 : std::max(1, options.samplesPerPixel);
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
                    if (options.pixelCentres) {
                        jx = jy = 0.5;
                    } else if (stratified) {
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

} // namespace refraction
