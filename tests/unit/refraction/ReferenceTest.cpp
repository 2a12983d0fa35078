// The Embree reference, limited to two interfaces, against the closed-form image of the exact
// sphere; its media rule (nested and overlapping glass), the surfaces it counts per pixel, and
// its basic behaviour (misses see the environment, trapped paths are counted).
#include "support/TestSupport.h"

#include "engine/asset/ModelLoader.h"
#include "engine/capture/Metrics.h"
#include "engine/render/Environment.h"
#include "refraction/ReferenceTracer.h"
#include "refraction/RefractionPlugin.h"

#include <glm/gtc/matrix_transform.hpp>

namespace {

constexpr int kSize = 96;

/** Closed form, supersampled on an 8x8 grid per pixel: exact Fresnel at the entry with the
 *  reflected environment, then the exact exit through the unit sphere. */
std::vector<float> closedForm(const render::Camera& camera,
                              const refraction::EnvironmentSampler& env, double ior) {
    std::vector<float> rgba(std::size_t(kSize) * kSize * 4, 0.0f);
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(camera.viewProjection()));
    for (int row = 0; row < kSize; ++row)
        for (int x = 0; x < kSize; ++x) {
            glm::dvec3 sum(0.0);
            int hits = 0;
            for (int s = 0; s < 64; ++s) {
                const double ndcX = (x + (s % 8 + 0.5) / 8) / kSize * 2 - 1;
                const int stratum = s / 8; // integer division: the sample's row in an 8x8 grid
                const double ndcY = (kSize - 1 - row + (stratum + 0.5) / 8) / kSize * 2 - 1;
                const glm::dvec4 n = inverse * glm::dvec4(ndcX, ndcY, -1, 1),
                                 f = inverse * glm::dvec4(ndcX, ndcY, 1, 1);
                const glm::dvec3 o = glm::dvec3(n) / n.w,
                                 d = glm::normalize(glm::dvec3(f) / f.w - o);
                const double b = glm::dot(o, d), c = glm::dot(o, o) - 1, disc = b * b - c;
                if (disc <= 0) {
                    sum += env.radiance(d, 0.0);
                    continue;
                }
                ++hits;
                const glm::dvec3 p1 = o + d * (-b - std::sqrt(disc));
                const double cosI = -glm::dot(d, p1), eta = 1 / ior;
                const double cosT = std::sqrt(1 - eta * eta * (1 - cosI * cosI));
                const double rs = (eta * cosI - cosT) / (eta * cosI + cosT),
                             rp = (cosI - eta * cosT) / (cosI + eta * cosT);
                const double fresnel = 0.5 * (rs * rs + rp * rp);
                const glm::dvec3 t1 = glm::refract(d, p1, eta);
                const glm::dvec3 p2 = p1 + t1 * (-2 * glm::dot(p1, t1));
                const glm::dvec3 t2 = glm::normalize(glm::refract(t1, -p2, ior));
                sum += fresnel * env.radiance(glm::reflect(d, p1), 0.0) +
                       (1 - fresnel) * env.radiance(t2, 0.0);
            }
            float* out = &rgba[(std::size_t(row) * kSize + std::size_t(x)) * 4];
            for (int k = 0; k < 3; ++k)
                out[k] = float(sum[k] / 64);
            out[3] = float(hits) / 64.0f;
        }
    return rgba;
}

capture::Image display(const std::vector<float>& hdr) {
    return {kSize, kSize, render::cpu::tonemap(hdr, 1.0f)};
}

TEST(Reference, TwoInterfaceSphereMatchesTheClosedForm) {
    const auto model = std::make_shared<const scene::Model>(asset::makeSphere(256));
    const scene::Model& sphere = *model;
    const scene::World world = scene::singleCharacterWorld(model);
    const refraction::EnvironmentSampler env(render::Environment::proceduralSky(512), 0.0f, 1.0f);
    const render::Camera camera =
        render::frameBounds(render::animatedBounds(sphere, -1), 1.0f, 0.6f, 0.3f, 0.2f, 1.15f);
    render::RenderSettings settings;
    settings.size = {kSize, kSize};
    for (double ior : {1.2, 1.5}) {
        auto glass = refraction::createPlugin()->parameters();
        ASSERT_TRUE(glass.set("ior", std::to_string(ior)).ok());
        refraction::ReferenceOptions options;
        options.samplesPerPixel = 64;
        options.twoInterfaces = true;
        auto traced =
            refraction::traceReference(world, 0.0, camera, env, settings, {}, glass, options);
        ASSERT_TRUE(traced.ok()) << traced.error().message;
        const auto exact = closedForm(camera, env, ior);
        std::vector<bool> mask(std::size_t(kSize) * kSize);
        for (std::size_t i = 0; i < mask.size(); ++i)
            mask[i] = traced->rgba[i * 4 + 3] == 1.0f && exact[i * 4 + 3] == 1.0f;
        const auto scores = capture::score(display(traced->rgba), display(exact), &mask);
        std::printf("reference vs closed form, sphere IOR %.1f: masked PSNR %.2f dB, SSIM %.4f "
                    "over %zu pixels\n",
                    ior, scores.psnr, scores.ssim, scores.pixels);
        EXPECT_GT(scores.pixels, 1000u);
        EXPECT_GE(scores.psnr, 35.0);
    }
}

TEST(Reference, GroundAndOpaqueMeshesAreShadedNotRefused) {
    // The unit sphere as an opaque mesh on the ground square: every pixel whose ray meets the
    // sphere or the ground (found in closed form) is lit, neither black nor the environment;
    // the rest see the environment exactly; no pixel is glass.
    const auto model = std::make_shared<const scene::Model>(asset::makeSphere(32));
    const scene::Model& sphere = *model;
    const scene::World world = scene::singleCharacterWorld(model);
    const refraction::EnvironmentSampler env(render::Environment::proceduralSky(64), 0.0f, 1.0f);
    const render::Camera camera =
        render::frameBounds(render::animatedBounds(sphere, -1), 1.0f, 0.7f, 0.0f, 0.5f);
    constexpr int size = 16;
    render::RenderSettings settings;
    settings.size = {size, size};
    settings.ground = true;
    const render::GroundPlane ground{-1.0f, glm::vec3(0.0f), 4.0f};
    auto glass = refraction::createPlugin()->parameters();
    ASSERT_TRUE(glass.set("method", "opaque").ok()); // the sphere is an opaque mesh now
    refraction::ReferenceOptions options;
    options.pixelCentres = true;
    auto traced =
        refraction::traceReference(world, 0.0, camera, env, settings, ground, glass, options);
    ASSERT_TRUE(traced.ok()) << traced.error().message;
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(camera.viewProjection()));
    int lit = 0, sky = 0;
    for (int row = 0; row < size; ++row)
        for (int x = 0; x < size; ++x) {
            const double ndcX = (x + 0.5) / size * 2 - 1,
                         ndcY = (size - 1 - row + 0.5) / size * 2 - 1;
            const glm::dvec4 n = inverse * glm::dvec4(ndcX, ndcY, -1, 1),
                             f = inverse * glm::dvec4(ndcX, ndcY, 1, 1);
            const glm::dvec3 o = glm::dvec3(n) / n.w, d = glm::normalize(glm::dvec3(f) / f.w - o);
            const double b = glm::dot(o, d), c = glm::dot(o, o) - 1;
            const double t = (-1.0 - o.y) / d.y;
            const glm::dvec3 onGround = o + t * d;
            const bool meets = b * b - c > 1e-3 ||
                               (t > 0 && std::abs(onGround.x) <= 4 && std::abs(onGround.z) <= 4);
            const float* px = &traced->rgba[(std::size_t(row) * size + std::size_t(x)) * 4];
            const glm::dvec3 colour(px[0], px[1], px[2]), behind = env.radiance(d, 0.0);
            EXPECT_EQ(px[3], 0.0f) << "no glass";
            if (meets) {
                EXPECT_GT(colour.r + colour.g + colour.b, 0.005) << "black at " << x << "," << row;
                EXPECT_GT(glm::length(colour - behind), 0.01) << "the sky at " << x << "," << row;
                ++lit;
            } else if (std::abs(b * b - c) > 1e-3) { // clear of the sphere's outline
                EXPECT_LT(glm::length(colour - behind), 1e-3) << x << "," << row;
                ++sky;
            }
        }
    EXPECT_GT(lit, size * size / 4);
    EXPECT_GT(sky, 0);
}

/** A world of spheres (centre, radius), each its own character. */
scene::World spheres(std::initializer_list<std::pair<glm::vec3, float>> placed) {
    const auto model = std::make_shared<const scene::Model>(asset::makeSphere(96));
    scene::World world;
    for (const auto& [centre, radius] : placed) {
        scene::Character c;
        c.model = model;
        c.placement.translation = glm::dvec3(centre);
        c.placement.scale = glm::dvec3(radius);
        c.glass = scene::GlassMode::All;
        world.characters.push_back(c);
    }
    return world;
}

struct Traced {
    capture::Image image;
    refraction::ReferenceImage hdr;
};

Traced traceSpheres(const scene::World& world, const char* ior = "1.5") {
    const refraction::EnvironmentSampler env(render::Environment::proceduralSky(128), 0.0f, 1.0f);
    render::Bounds box; // the same camera for every world
    box.add(glm::vec3(-1.3f));
    box.add(glm::vec3(1.3f));
    const render::Camera camera = render::frameBounds(box, 1.0f, 0.7f, 0.0f, 0.0f, 0.8f);
    render::RenderSettings settings;
    settings.size = {kSize, kSize};
    auto glass = refraction::createPlugin()->parameters();
    EXPECT_TRUE(glass.set("ior", ior).ok());
    refraction::ReferenceOptions options;
    options.samplesPerPixel = 4;
    auto traced = refraction::traceReference(world, 0.0, camera, env, settings, {}, glass, options);
    EXPECT_TRUE(traced.ok()) << (traced.ok() ? "" : traced.error().message);
    if (!traced)
        return {};
    return {display(traced->rgba), std::move(*traced)};
}

TEST(Reference, GlassInsideGlassOfTheSameIndexIsOneMedium) {
    // A sphere inside a larger one of the same index: entering it changes no medium (the rule:
    // a stack of entered solids), so the pair looks like the large sphere alone. Crossing every
    // surface as glass-to-air instead would refract at the inner sphere and differ.
    const Traced alone = traceSpheres(spheres({{glm::vec3(0.0f), 1.0f}}));
    const Traced nested =
        traceSpheres(spheres({{glm::vec3(0.0f), 1.0f}, {glm::vec3(0.1f, 0.0f, 0.0f), 0.4f}}));
    const auto scores = capture::score(nested.image, alone.image);
    std::printf("reference: a sphere nested in another of the same index vs the outer alone: "
                "PSNR %.2f dB\n",
                scores.psnr);
    EXPECT_GE(scores.psnr, 40.0);
    EXPECT_EQ(nested.hdr.trappedSamples, 0u);
    // Four surfaces on the lines of sight through the inner sphere, two elsewhere.
    ASSERT_GE(nested.hdr.surfaceHistogram.size(), 5u);
    EXPECT_GT(nested.hdr.surfaceHistogram[4], 100u);
    EXPECT_GT(nested.hdr.surfaceHistogram[2], nested.hdr.surfaceHistogram[4]);
    EXPECT_EQ(nested.hdr.surfaceHistogram[1] + nested.hdr.surfaceHistogram[3], 0u);
}

TEST(Reference, GlassBehindGlassIsRefractedAtItsOwnSurfaces) {
    // A sphere behind another changes the image through the front one (its rays pass through
    // four interfaces), and nothing is trapped.
    const Traced front = traceSpheres(spheres({{glm::vec3(-0.3f, 0.0f, 0.8f), 0.6f}}));
    const Traced both = traceSpheres(
        spheres({{glm::vec3(-0.3f, 0.0f, 0.8f), 0.6f}, {glm::vec3(0.4f, 0.0f, -0.8f), 0.8f}}));
    std::size_t changed = 0;
    for (std::size_t i = 0; i < front.image.rgba.size(); i += 4)
        if (front.hdr.rgba[i + 3] > 0.5f && both.hdr.rgba[i + 3] > 0.5f &&
            std::abs(int(front.image.rgba[i]) - int(both.image.rgba[i])) > 8)
            ++changed;
    EXPECT_GT(changed, 100u) << "the far sphere should show through the near one";
    EXPECT_EQ(both.hdr.trappedSamples, 0u);
}

} // namespace
