// Embree reference tracer.
#include "refraction/ReferenceTracer.h"

#include "Optics.h"

#include "engine/deform/CpuDeformer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <thread>
#include <unistd.h>

namespace refraction {
namespace {

using glm::dvec3;

/** The environment exactly as the GPU samples it at mip level 0 (see sampleEnvironment). */
class EnvironmentLookup {
public:
    EnvironmentLookup(const asset::HdrImage& image, float rotation, float intensity)
        : mImage(image), mRotation(rotation), mIntensity(intensity) {}
    dvec3 operator()(dvec3 d) const { return sampleEnvironment(mImage, mRotation, mIntensity, d); }

private:
    const asset::HdrImage& mImage;
    float mRotation, mIntensity;
};

struct Surface {

    std::vector<dvec3> positions, normals; // world
    std::vector<std::uint32_t> indices;
    Optics optics;
};

struct Hit {
    bool hit = false;
    double t = 0.0;
    dvec3 point, shadingNormal, geometricNormal;
    const Surface* surface = nullptr;
};

double fresnelEntry(const std::string& mode, double cosI, double eta) {
    if (mode == "off")
        return 0.0;
    if (mode == "schlick") {
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

class Tracer {
public:
    Tracer(const std::vector<Surface>& surfaces, const EnvironmentLookup& env,
           const ReferenceOptions& options, const std::string& fresnelMode, double epsilon)
        : mSurfaces(surfaces), mEnv(env), mOptions(options), mFresnel(fresnelMode),
          mEpsilon(epsilon) {
        mDevice = rtcNewDevice(nullptr);
        mScene = rtcNewScene(mDevice);
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

    Hit intersect(const dvec3& origin, const dvec3& dir) const {
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
        Hit h;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            return h;
        const Surface& s = mSurfaces[rh.hit.geomID];
        const std::uint32_t* tri = &s.indices[std::size_t(rh.hit.primID) * 3];
        const double u = rh.hit.u, v = rh.hit.v;
        h.hit = true;
        h.t = rh.ray.tfar;
        h.surface = &s;
        h.point =
            (1 - u - v) * s.positions[tri[0]] + u * s.positions[tri[1]] + v * s.positions[tri[2]];
        h.shadingNormal = glm::normalize((1 - u - v) * s.normals[tri[0]] + u * s.normals[tri[1]] +
                                         v * s.normals[tri[2]]);
        h.geometricNormal = glm::normalize(glm::cross(s.positions[tri[1]] - s.positions[tri[0]],
                                                      s.positions[tri[2]] - s.positions[tri[0]]));
        return h;
    }

    /** Radiance of channel `c` along a ray entering glass at `h` (refracted), through the glass
     *  with real TIR, and on after it leaves. */
    double inside(const Hit& entry, const dvec3& dir, int c, int depth, std::uint32_t& rng,
                  std::size_t& trapped) const {
        const Optics& o = entry.surface->optics;
        const double ior = o.ior[c], sigma = o.sigma[c];
        dvec3 n = entry.shadingNormal;
        if (glm::dot(n, dir) > 0)
            n = -n;
        dvec3 d;
        if (!refractRay(dir, n, 1.0 / ior, d))
            return 0.0;
        dvec3 p = entry.point;
        double length = 0.0;
        for (int bounce = 0;; ++bounce) {
            const Hit h = intersect(p, d);
            if (!h.hit) // an open mesh: the ray leaves through the hole
                return mEnv(d)[c] * std::exp(-sigma * length);
            length += h.t;
            dvec3 out = h.shadingNormal;
            if (glm::dot(out, d) < 0)
                out = -out;
            dvec3 t;
            if (refractRay(d, -out, ior, t))
                return outside(h.point, t, c, depth + 1, rng, trapped) * std::exp(-sigma * length);
            if (bounce >= mOptions.maxBounces) {
                ++trapped;
                return 0.0;
            }
            d = glm::reflect(d, out);
            p = h.point;
        }
    }

    /** Radiance of channel `c` arriving along a ray in air from `origin`. */
    double outside(const dvec3& origin, const dvec3& dir, int c, int depth, std::uint32_t& rng,
                   std::size_t& trapped) const {
        if (mOptions.twoInterfaces || depth > 2 * mOptions.maxBounces)
            return mEnv(dir)[c];
        const Hit h = intersect(origin, dir);
        if (!h.hit)
            return mEnv(dir)[c];
        dvec3 n = h.shadingNormal;
        if (glm::dot(n, dir) > 0)
            n = -n;
        const Optics& o = h.surface->optics;
        const double f = fresnelEntry(mFresnel, -glm::dot(dir, n), 1.0 / o.ior[c]);
        if (random01(rng) < f)
            return outside(h.point, glm::reflect(dir, n), c, depth + 1, rng, trapped);
        return o.baseColor[c] * inside(h, dir, c, depth + 1, rng, trapped);
    }

    /** Colour of one camera ray; `glass` reports whether it hit glass. */
    dvec3 primary(const dvec3& origin, const dvec3& dir, bool& glass, std::uint32_t& rng,
                  std::size_t& trapped) const {
        const Hit h = intersect(origin, dir);
        glass = h.hit;
        if (!h.hit)
            return mEnv(dir);
        const Optics& o = h.surface->optics;
        dvec3 n = h.shadingNormal;
        if (glm::dot(n, dir) > 0)
            n = -n;
        const double f = fresnelEntry(mFresnel, -glm::dot(dir, n), 1.0 / o.ior.g);
        const dvec3 reflected = mEnv(glm::reflect(dir, n));
        dvec3 transmitted;
        for (int c = 0; c < 3; ++c)
            transmitted[c] = inside(h, dir, c, 0, rng, trapped);
        const dvec3 glassColor = f * reflected + (1 - f) * dvec3(o.baseColor) * transmitted;
        return double(o.transmission) * glassColor;
    }

private:
    const std::vector<Surface>& mSurfaces;
    const EnvironmentLookup& mEnv;
    const ReferenceOptions& mOptions;
    std::string mFresnel;
    double mEpsilon;
    RTCDevice mDevice = nullptr;
    RTCScene mScene = nullptr;
};

} // namespace

core::Result<ReferenceImage>
traceReference(const scene::Model& model, const anim::Pose& pose, const render::Camera& camera,
               const asset::HdrImage& environment, const render::RenderSettings& settings,
               const plugin::ParameterSet& glass, const ReferenceOptions& options) {
    const std::string where = "refraction::traceReference(): ";
    if (settings.ground)
        return core::Error{where + "the ground plane is not traced; render without --ground"};
    std::vector<Surface> surfaces;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& instance : deform::deformScene(model, pose)) {
        const scene::Mesh& mesh = model.meshes[std::size_t(instance.mesh)];
        for (std::size_t p = 0; p < instance.primitives.size(); ++p) {
            const scene::Primitive& primitive = mesh.primitives[p];
            if (!isGlass(glass, model, primitive))
                return core::Error{where + model.sourceName + ": node " +
                                   std::to_string(instance.node) + " primitive " +
                                   std::to_string(p) +
                                   " is opaque; the reference traces glass only (use --glass all)"};
            const auto world = deform::toWorld(instance.primitives[p], instance.meshToWorld);
            Surface s;
            s.positions = world.positions;
            s.normals = world.normals;
            s.indices = primitive.indices;
            const int material = primitive.material;
            s.optics =
                opticsFor(glass, material >= 0 ? &model.materials[std::size_t(material)] : nullptr);
            if (!s.optics.dispersion)
                s.optics.ior = glm::vec3(s.optics.ior.g);
            for (const auto& v : s.positions) {
                lo = glm::min(lo, v);
                hi = glm::max(hi, v);
            }
            surfaces.push_back(std::move(s));
        }
    }
    const EnvironmentLookup env(environment, settings.environmentRotation,
                                settings.environmentIntensity);
    const double epsilon = surfaces.empty() ? 1e-6 : 1e-5 * glm::length(hi - lo);
    const Tracer tracer(surfaces, env, options, glass.choice("fresnel"), epsilon);

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
    const unsigned threads =
        options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    const bool bar = options.progress && isatty(2);
    auto work = [&] {
        std::size_t localTrapped = 0;
        for (int row = nextRow++; row < h; row = nextRow++) {
            for (int x = 0; x < w; ++x) {
                dvec3 sum(0.0);
                int glassSamples = 0;
                for (int s = 0; s < spp; ++s) {
                    std::uint32_t rng = std::uint32_t(row * 73856093) ^
                                        std::uint32_t(x * 19349663) ^ std::uint32_t(s * 83492791);
                    double jx = random01(rng), jy = random01(rng);
                    if (stratified) {
                        jx = (double(s % grid) + jx) / grid;
                        jy = (double(s / grid) + jy) / grid;
                    }
                    const double ndcX = (x + jx) / w * 2.0 - 1.0,
                                 ndcY = (h - 1 - row + jy) / h * 2.0 - 1.0;
                    const glm::dvec4 nearPoint = inverse * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
                    const glm::dvec4 farPoint = inverse * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
                    const dvec3 origin = dvec3(nearPoint) / nearPoint.w;
                    const dvec3 dir = glm::normalize(dvec3(farPoint) / farPoint.w - origin);
                    bool glassHit = false;
                    sum += tracer.primary(origin, dir, glassHit, rng, localTrapped);
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
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back(work);
    for (auto& t : pool)
        t.join();
    if (bar)
        std::fprintf(stderr, "\n");
    image.trappedSamples = trapped.load();
    return image;
}

using dvec3 = glm::dvec3;

glm::dvec3 sampleEnvironment(const asset::HdrImage& image, float rotation, float intensity,
                             glm::dvec3 d) {
    const double c = std::cos(rotation), s = std::sin(rotation);
    d = glm::normalize(dvec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z));
    const double u = 0.5 + std::atan2(d.x, -d.z) / (2.0 * M_PI);
    const double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / M_PI;
    const double x = u * image.width - 0.5, y = v * image.height - 0.5;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    dvec3 sum(0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const int xi = ((x0 + i) % image.width + image.width) % image.width;
            const int yi = std::clamp(y0 + j, 0, image.height - 1);
            const float* p =
                &image.rgb[(std::size_t(yi) * std::size_t(image.width) + std::size_t(xi)) * 3];
            sum += (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * dvec3(p[0], p[1], p[2]);
        }
    return sum * double(intensity);
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
