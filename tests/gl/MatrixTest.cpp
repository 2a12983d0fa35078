// The test matrix: every feature crossed with every method (docs/accuracy.md, "The matrix"). Each
// row is a world of one feature (MatrixWorlds.h, the project's scenes and models); each cell
// scores a method at one sample a pixel against the reference's 16 jittered rays (masked PSNR),
// and the trace through each pixel's centre against the reference's deterministic evaluation
// (the same model, docs/methods.md: agreement to 40 dB or more but where a row says why not).
// Each method also accumulates kStillFrames still frames (temporal accumulation, one jittered
// sample a frame), scored against the same reference (the "accumulated" lines).
// Floors come from measurement (a dB or two below it); a new feature adds its row.
// GLASS_MATRIX_SIZE=N renders at N x N and prints the row as markdown without checking floors
// (scripts/matrix, for docs/accuracy.md); GLASS_MATRIX_OUT=DIR writes each row's frames and
// references there, to be looked at.
#include "MatrixWorlds.h"
#include "support/GlTest.h"

#include "engine/asset/HdrImage.h"
#include "engine/capture/Image.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

namespace {

using test::WorldRig;
using namespace test::matrix;
using Type = scene::Light::Type;

constexpr const char* kMethods[] = {"sir", "isr", "dir", "trace", "hybrid"};
constexpr int kStillFrames = 8;

struct Row {
    const char* name;
    std::function<scene::World()> world;
    /** Floors: SIR, ISR, DIR, trace, hybrid against the sampled reference, then the trace at
     *  pixel centres against the deterministic one. */
    std::array<double, 6> floors;
    double time = 0.0;
    std::vector<std::pair<const char*, const char*>> parameters = {};
    int subdivision = 0;
    bool hdr = false; ///< lit by assets/env/sunset_sky.hdr
    /** Why the trace and the deterministic reference part by more than 40 dB (shown). */
    const char* why = "";
};

#ifdef GLASS_SOURCE_DIR
scene::World project(const char* scene) {
    return test::projectScene(scene);
}
scene::World figure(const char* file) {
    return test::generatedWorld(file);
}
/** The figure's walk crossfading to its idle clip over 0.4 s from 0.2 s, or idling with its
 *  wave added on top at 0.7. */
scene::World blended(scene::World world, bool additive) {
    const scene::Model& model = *world.characters[0].model;
    scene::Performance& p = world.characters[0].performance;
    if (additive) {
        p = scene::Performance::single(*model.findAnimation("idle"));
        scene::Layer& wave = p.layers.emplace_back();
        wave.clip = *model.findAnimation("wave");
        wave.weight = 0.7;
        wave.additive = true;
    } else {
        p.transitions = {{0.2, *model.findAnimation("idle"), 0.4}};
    }
    return world;
}
#endif

std::vector<Row> rows() {
    const glm::vec3 warm(1.0f, 0.85f, 0.7f), cool(0.6f, 0.75f, 1.0f);
    const char* filtered = "at one sample the trace reads its entry's textures filtered over the "
                           "pixel, as the walk does; the deterministic reference at one point";
    // One row a feature, kept as a table.
    // clang-format off
    std::vector<Row> r = {
        {"no lights", sphere, {17.5, 31, 41, 40.5, 41, 60}},
        {"a directional light",
         [=] {
             return lit(sphere(), {light(Type::Directional, {}, {0.3f, -1.0f, -0.5f}, warm, 3)});
         },
         {17.5, 31, 39, 39, 39, 60}},
        {"a point light",
         [=] { return lit(sphere(), {light(Type::Point, {1.5f, 1.5f, 2.0f}, {}, warm, 30)}); },
         {17.5, 30.5, 38.5, 38.5, 38.5, 60}},
        {"a spot light",
         [=] {
             return lit(sphere(), {light(Type::Spot, {0.5f, 2.0f, 2.5f}, {-0.2f, -0.7f, -0.8f},
                                         warm, 60)});
         },
         {17.5, 31, 40, 39.5, 40, 60}},
        {"sixteen lights",
         [=] {
             std::vector<scene::PlacedLight> many;
             for (int i = 0; i < 16; ++i) {
                 const float a = float(i) * 0.3927f;
                 const glm::vec3 at(2.5f * std::cos(a), 1.0f + 0.1f * float(i % 4),
                                    2.5f * std::sin(a));
                 many.push_back(light(i % 3 == 0 ? Type::Spot : Type::Point, at,
                                      {-std::cos(a), -0.4f, -std::sin(a)}, i % 2 ? warm : cool, 6));
             }
             return lit(sphere(), many);
         },
         {17.5, 29.5, 33.5, 33.5, 33.5, 60}},
        {"the ground",
         [] {
             scene::World w = sphere();
             w.ground = true;
             return w;
         },
         {17, 28, 36.5, 37.5, 36.5, 52}},
        {"an HDR environment", sphere, {18.5, 22, 28.5, 28.5, 28.5, 55}, 0.0, {}, 0, true},
        {"an opaque part inside", [] { return project("sphere_with_core.json"); },
         {18.5, 19, 19, 31.5, 19, 56}},
        {"an opaque character behind", besideOpaque, {24, 22, 27.5, 35, 27.5, 45}},
        {"glass textures", texturedGlass, {20.5, 24.5, 25.5, 25.5, 25.5, 36}, 0.0, {}, 0, false,
         filtered},
        {"glass textures, the two surfaces' capture", texturedGlass,
         {20.5, 24.5, 25.5, 25.5, 25.5, 36}, 0.0, {{"surfaces", "two-surface"}}, 0, false,
         filtered},
        {"glass textures past K layers", texturedGlass, {19.5, 22.5, 22.5, 25, 25, 55}, 0.0,
         {{"layer-capacity", "1"}}},
        {"a normal map", normalMapped, {16.5, 21.5, 22, 21, 21.5, 21}, 0.0, {}, 0, false,
         filtered},
        {"material layers on glass", layeredGlass, {18, 31, 42.5, 42.5, 42.5, 60}},
        {"a variant", variant, {18.5, 26.5, 35.5, 35.5, 35, 58}},
        {"rough glass", [] { return glassSphere(glassMaterial(glm::vec3(1.0f), 0.35f)); },
         {17, 22, 21.5, 21.5, 21.5, 61}},
        {"dispersion", sphere, {18, 31.5, 41, 40.5, 41, 60}, 0.0,
         {{"dispersion", "1.5"}, {"dispersion-search", "per-channel"}}},
        {"a tint without volume", sphere, {14, 28.5, 40.5, 40.5, 40.5, 61}, 0.0,
         {{"tint", "1,0.6,0.2"}}},
        {"instancing", instanced, {16, 14, 16.5, 21, 19, 38}, 0.0, {}, 0, false,
         "four pixels whose centre rays graze where two spheres' outlines meet"},
        {"mirrored and double-sided", mirroredAndOpen, {26, 27, 30, 31, 30.5, 55}},
        {"interpenetrating coloured parts", [] { return robot(false); },
         {20, 15.5, 24, 30, 26, 59}},
        {"black and metal forced to glass", [] { return robot(true); },
         {19.5, 15.5, 23.5, 27.5, 25, 59}},
        {"morph targets and absorption", [] { return figure("glass_figure.glb"); },
         {14.5, 26, 26.5, 25, 26, 41}, 0.3, {{"dispersion-search", "per-channel"}}},
        {"a crossfade", [] { return blended(figure("glass_figure.glb"), false); },
         {17, 26, 26.5, 26, 26.5, 38}, 0.4, {{"dispersion-search", "per-channel"}}, 0, false,
         "five pixels whose centre rays graze the arms and legs, where float and double part "
         "ways"},
        {"an animated glass material", animatedGlass, {20, 31.5, 43, 43, 43, 62}, 0.7},
        {"an additive layer", [] { return blended(figure("glass_figure.glb"), true); },
         {18, 25.5, 26, 25, 26, 47}, 0.8, {{"dispersion-search", "per-channel"}}},
        {"subdivision", [] { return figure("glass_figure.glb"); }, {14.5, 25.5, 27, 25, 26, 40},
         0.3, {{"dispersion-search", "per-channel"}}, 1},
        {"characters overlapping", [] { return project("glass_pair.json"); },
         {17, 19.5, 19.5, 20.5, 20, 27.5}, 0.5, {{"dispersion-search", "per-channel"}}, 0, false,
         "the parts figure's hammered head reflects totally inside, where float and double part "
         "ways over a few bounces"},
    };
    // clang-format on
    return r;
}

/** A row as GoogleTest prints a parameter: its name. */
void PrintTo(const Row& row, std::ostream* out) {
    *out << row.name;
}

class Matrix : public test::GlTest, public ::testing::WithParamInterface<Row> {};

/** A row's name as a test's and a file's: letters and digits, '_' for the rest. */
std::string rowName(const Row& row) {
    std::string name;
    for (const char* c = row.name; *c; ++c)
        name += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
    return name;
}

/** The size the matrix renders at: 128, or GLASS_MATRIX_SIZE (the floors are for 128). */
int matrixSize() {
    const char* size = std::getenv("GLASS_MATRIX_SIZE");
    return size && std::atoi(size) > 0 ? std::atoi(size) : 128;
}

TEST_P(Matrix, EveryMethodAgreesWithTheReference) {
    const Row& row = GetParam();
    const int size = matrixSize();
    std::optional<asset::HdrImage> hdr;
    if (row.hdr) {
        auto loaded = asset::loadHdr(std::string(GLASS_SOURCE_DIR) + "/assets/env/sunset_sky.hdr");
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        hdr = std::move(*loaded);
    }
    WorldRig rig(row.world(), context(), size, hdr ? &*hdr : nullptr);
    if (row.subdivision > 0)
        rig.setSubdivisionLevel(row.subdivision);
    for (const auto& [key, value] : row.parameters)
        rig.set(key, value);
    const WorldRig::Reference sampled = rig.reference(row.time);
    const WorldRig::Reference exact = rig.reference(row.time, WorldRig::Evaluation::Deterministic);
    const char* out = std::getenv("GLASS_MATRIX_OUT");
    auto keep = [&](const std::string& what, const capture::Image& image) {
        if (out) {
            EXPECT_TRUE(capture::writePng(
                            std::string(out) + "/" + rowName(row) + "." + what + ".png", image)
                            .ok());
        }
    };
    keep("reference", sampled.image);
    keep("deterministic", exact.image);
    std::array<double, 6> scores{};
    std::array<double, 5> accumulated{};
    for (std::size_t m = 0; m < std::size(kMethods); ++m) {
        rig.set("method", kMethods[m]);
        const capture::Image frame = rig.render(row.time);
        keep(kMethods[m], frame);
        scores[m] = capture::score(frame, sampled.image, &sampled.mask).psnr;
        rig.temporal.enabled = true;
        capture::Image still;
        for (int k = 0; k < kStillFrames; ++k)
            still = rig.render(row.time);
        rig.temporal.enabled = false;
        keep(std::string(kMethods[m]) + "-accumulated", still);
        accumulated[m] = capture::score(still, sampled.image, &sampled.mask).psnr;
    }
    rig.set("method", "trace");
    rig.set("outline-aa", "off"); // one ray through each pixel's centre, as the reference
    const capture::Image centres = rig.render(row.time);
    keep("trace-centres", centres);
    scores[5] = capture::score(centres, exact.image, &exact.mask).psnr;
    std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %s |\n", row.name, scores[0],
                scores[1], scores[2], scores[3], scores[4], scores[5], row.why);
    std::printf("accumulated | %s | %.2f | %.2f | %.2f | %.2f | %.2f |\n", row.name, accumulated[0],
                accumulated[1], accumulated[2], accumulated[3], accumulated[4]);
    if (size != 128)
        return; // a table for the docs, not a check
    const char* names[] = {"SIR", "ISR", "DIR", "trace", "hybrid", "trace at pixel centres"};
    for (std::size_t i = 0; i < scores.size(); ++i)
        EXPECT_GE(scores[i], row.floors[i]) << row.name << ", " << names[i];
    // Accumulating still frames averages jittered samples: no method moves away from the
    // reference, and the trace, whose one sample a frame follows the pixel's jittered path,
    // comes closer on every row (1.9 dB or more at 128x128).
    for (std::size_t i = 0; i < accumulated.size(); ++i)
        EXPECT_GE(accumulated[i], scores[i] - 0.25) << row.name << ", " << names[i];
    EXPECT_GE(accumulated[3], scores[3] + 1.0) << row.name << ", the trace accumulated";
}

INSTANTIATE_TEST_SUITE_P(Features, Matrix, ::testing::ValuesIn(rows()),
                         [](const ::testing::TestParamInfo<Row>& param) {
                             return rowName(param.param);
                         });

} // namespace
