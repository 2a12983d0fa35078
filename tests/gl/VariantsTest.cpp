// glTF as the ecosystem's tools write it: Draco, meshopt, quantized, texture-transformed and WebP
// variants made at test time by glTF-Transform's CLI (scripts/npm-deps installs it, pinned by
// tests/variants/package-lock.json) and gltfpack, of the default figure and the shared samples,
// and the Khronos variants in ../shared/assets/khronos. Each variant deforms like its source (CPU
// and GPU, within the quantisation step) and its frames match its source's goldens.
#include "support/GlTest.h"
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/GltfLoader.h"
#include "engine/capture/Image.h"
#include "engine/capture/Metrics.h"
#include "engine/deform/CpuDeformer.h"
#include "engine/deform/GpuDeformer.h"
#include "engine/render/Camera.h"
#include "engine/render/Environment.h"
#include "engine/render/Renderer.h"
#include "engine/render/WorldLoader.h"
#include "refraction/ReferenceTracer.h"
#include "refraction/RefractionPlugin.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <unordered_map>

namespace {

namespace fs = std::filesystem;

/** A model the tools rewrite, with what its tests need to know. */
struct Source {
    std::string name;
    fs::path file;
    int framesPerSecond;    ///< its keyframe rate: gltfpack resamples animations at this rate
    bool textured;          ///< has images, so a WebP variant means something
    std::string goldenCase; ///< tests/golden/<case>.json rendering the source ("" for none)
};

/** One tool run, and what its output's deformation is compared with at Precision::Fine. */
struct Tool {
    std::string name;
    std::string command; ///< {in} and {out} are filled in
    /** The variant of the same source to compare with ("" for the source itself): meshopt
     *  compression is lossless over quantised data, so gltfpack's compressed outputs are held
     *  to its uncompressed one, made with the same quantisation. */
    std::string twin;
    /** Compared in the rest pose only: gltfpack quantises weights to 8 bits, whatever is asked,
     *  and glTF-Transform's meshopt command compresses the animation through meshopt's lossy
     *  quaternion and exponential filters. Their frames are compared with the goldens. */
    bool restOnly = false;
};

/** A tool's output for one source. */
struct Variant {
    std::string name; ///< source.tool
    const Source* source;
    fs::path file;
    Tool tool;
};

std::vector<Source> sources() {
    std::vector<Source> list = {{"figure",
                                 fs::path(GLASS_SOURCE_DIR) / "assets/models/glass_figure.glb", 30,
                                 false, "figure_dir_two_passes_subdiv1"}};
    if (!test::sharedDir().empty()) {
        const fs::path gltf = test::sharedDir() / "assets/gltf";
        list.push_back({"cesiumman", gltf / "CesiumMan/CesiumMan.glb", 24, true, "cesiumman"});
        list.push_back({"fox", gltf / "Fox/Fox.glb", 24, true, "fox_walk"});
        list.push_back({"morphcube", gltf / "AnimatedMorphCube/AnimatedMorphCube.glb", 30, false,
                        "animated_morph_cube"});
    }
    return list;
}

/** How finely the tools quantise: their defaults (what users ship), or 16 bits for every
 *  attribute they allow, so that deformation can be compared within a small step. */
enum class Precision { Default, Fine };

/** The tool runs for `source`. */
std::vector<Tool> tools(const Source& source, Precision precision) {
    const std::string gltfTransform =
        (fs::path(GLASS_SOURCE_DIR) / "build/variants/node_modules/.bin/gltf-transform").string();
    const bool fine = precision == Precision::Fine;
    const std::string bits = fine ? " --quantize-position 16 --quantize-normal 16"
                                    " --quantize-texcoord 16"
                                  : "";
    // gltfpack keeps every keyframe when it resamples at the source's own rate, and its
    // animation quantisation is set finer than its default so that only geometry differs.
    const std::string gltfpack = "gltfpack -af " + std::to_string(source.framesPerSecond) +
                                 " -ar 16 -at 24 -as 24" + (fine ? " -vp 16 -vn 16 -vt 16" : "") +
                                 " -i {in} -o {out}";
    std::vector<Tool> list = {
        {"gt-draco",
         gltfTransform + " draco {in} {out}" + bits + (fine ? " --quantize-generic 16" : ""), "",
         false},
        {"gt-meshopt",
         gltfTransform + " meshopt {in} {out}" + bits + (fine ? " --quantize-weight 16" : ""), "",
         true},
        {"gt-quantize",
         gltfTransform + " quantize {in} {out}" + bits + (fine ? " --quantize-weight 16" : ""), "",
         false},
        {"gp-quantize", gltfpack, "", true},
        // -cc adds meshopt's lossy filters (inverse bind matrices, rotations): -c alone is
        // lossless over the quantised data, so the fine set uses it.
        {"gp-meshopt", gltfpack + (fine ? " -c" : " -cc"), "gp-quantize", false},
        {"gp-fallback", gltfpack + " -cf", "gp-quantize", false}};
    if (source.textured && !fine)
        list.push_back({"gt-webp", gltfTransform + " webp {in} {out}", "", false});
    return list;
}

std::string replaced(std::string text, const std::string& key, const std::string& value) {
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at))
        text.replace(at, key.size(), value), at += value.size();
    return text;
}

/** Where the variants and their frames go: build/variants-out. */
fs::path outDir() {
    return fs::path(GLASS_BIN_DIR).parent_path() / "variants-out";
}

/** Every variant at `precision`, made once for the whole test program in outDir(). */
const std::vector<Variant>& variants(Precision precision) {
    static const std::vector<Source> kSources = sources();
    auto make = [](Precision p) {
        std::vector<Variant> list;
        const fs::path out = outDir();
        fs::create_directories(out);
        for (const Source& source : kSources)
            for (const Tool& tool : tools(source, p)) {
                const std::string name =
                    source.name + "." + tool.name + (p == Precision::Fine ? "-16" : "");
                const fs::path file = out / (name + ".glb");
                fs::remove(file);
                std::string output;
                const std::string line = replaced(
                    replaced(tool.command, "{in}", source.file.string()), "{out}", file.string());
                const int status = test::runCommand(line, &output);
                if (status != 0 || !fs::exists(file))
                    ADD_FAILURE() << line << " failed (" << status << "):\n" << output;
                else
                    list.push_back({name, &source, file, tool});
            }
        return list;
    };
    if (precision == Precision::Fine) {
        static const std::vector<Variant> kFine = make(Precision::Fine);
        return kFine;
    }
    static const std::vector<Variant> kDefault = make(Precision::Default);
    return kDefault;
}

/** Every vertex of deformed `instances` in world space; `positions(i, p)` gives instance i's
 *  primitive p in mesh space (the CPU oracle's own, or the GPU deform pass's). */
template <typename Positions>
std::vector<glm::dvec3> worldVertices(const std::vector<deform::DeformedInstance>& instances,
                                      Positions positions) {
    std::vector<glm::dvec3> out;
    for (std::size_t i = 0; i < instances.size(); ++i)
        for (std::size_t p = 0; p < instances[i].primitives.size(); ++p)
            for (const glm::dvec3& v : positions(i, p))
                out.push_back(glm::dvec3(instances[i].meshToWorld * glm::dvec4(v, 1.0)));
    return out;
}

std::vector<glm::dvec3> cpuVertices(const std::vector<deform::DeformedInstance>& instances) {
    return worldVertices(instances, [&](std::size_t i, std::size_t p) {
        return instances[i].primitives[p].positions;
    });
}

double diagonal(const std::vector<glm::dvec3>& points) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : points)
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    return points.empty() ? 0.0 : glm::length(hi - lo);
}

/** The largest distance from a point of `a` to the nearest point of `b`, found on a grid of
 *  `cell`-sized cells; a point with nothing within a cell counts as `cell` away. The tools
 *  reorder and weld vertices, so the two are compared as point sets. */
double farthestFromNearest(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b,
                           double cell) {
    auto key = [&](glm::ivec3 c) {
        return (std::int64_t(c.x) * 73856093) ^ (std::int64_t(c.y) * 19349663) ^
               (std::int64_t(c.z) * 83492791);
    };
    std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
    for (std::size_t i = 0; i < b.size(); ++i)
        grid[key(glm::ivec3(glm::floor(b[i] / cell)))].push_back(i);
    double worst = 0.0;
    for (const glm::dvec3& p : a) {
        const glm::ivec3 c(glm::floor(p / cell));
        double nearest = cell;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = grid.find(key(c + glm::ivec3(dx, dy, dz)));
                    if (it != grid.end())
                        for (std::size_t i : it->second)
                            nearest = std::min(nearest, glm::length(b[i] - p));
                }
        worst = std::max(worst, nearest);
    }
    return worst;
}

/** At Precision::Fine every attribute is quantised to 16 bits of its range (the mesh's extent
 *  for positions, 0..1 for weights): a vertex may move half a step per axis, and a weight's step
 *  moves it by a step of the distance between its joints' transforms of it. Two steps of the
 *  world-space diagonal bound both. */
constexpr double kQuantisationStep = 2.0 / 65535.0;

class Variants : public test::GlTest {
protected:
    /** `variant` deforms like `source` at several times of the first clip (or in the rest pose
     *  only), CPU and GPU: no vertex of either is farther than `tolerance` (a fraction of the
     *  diagonal) from the other's nearest. */
    static void expectDeformsLike(const scene::Model& source, const scene::Model& variant,
                                  const std::string& name, double tolerance,
                                  bool restOnly = false) {
        auto deformer = deform::GpuDeformer::create(variant, shaders());
        ASSERT_TRUE(deformer.ok()) << deformer.error().message;
        const int clip = restOnly || source.animations.empty() ? -1 : 0;
        const double duration = clip < 0 ? 0.0 : source.animations[0].duration;
        for (double fraction : {0.0, 0.37, 0.81}) {
            if (clip < 0 && fraction > 0.0)
                break;
            const double time = fraction * duration;
            const std::vector<glm::dvec3> expected =
                cpuVertices(deform::deformScene(source, anim::evaluate(source, clip, time)));
            const double size = diagonal(expected);
            const anim::Pose pose = anim::evaluate(variant, clip, time);
            const auto cpu = deform::deformScene(variant, pose);
            (*deformer)->update(pose);
            for (const bool gpu : {false, true}) {
                const std::vector<glm::dvec3> got =
                    gpu ? worldVertices(cpu,
                                        [&](std::size_t i, std::size_t p) {
                                            return (*deformer)->download(i, p).positions;
                                        })
                        : cpuVertices(cpu);
                ASSERT_FALSE(got.empty()) << name;
                const double cell = 8.0 * tolerance * size;
                const double error = std::max(farthestFromNearest(got, expected, cell),
                                              farthestFromNearest(expected, got, cell)) /
                                     size;
                EXPECT_LE(error, tolerance)
                    << name << (gpu ? " GPU" : " CPU") << " at t=" << time << ": a vertex is "
                    << error * 65535.0 << " 16-bit steps of the diagonal from its source";
            }
        }
    }
};

TEST_F(Variants, ToolsWriteVariantsThatLoadAndDeformLikeTheirSources) {
    const std::vector<Variant>& all = variants(Precision::Fine);
    ASSERT_FALSE(all.empty());
    for (const Variant& v : all) {
        SCOPED_TRACE(v.name);
        fs::path reference = v.source->file;
        if (!v.tool.twin.empty()) {
            const std::string twin = v.source->name + "." + v.tool.twin + "-16";
            const auto it = std::find_if(all.begin(), all.end(),
                                         [&](const Variant& w) { return w.name == twin; });
            ASSERT_NE(it, all.end()) << twin << " was not made";
            reference = it->file;
        }
        auto source = asset::loadGltf(reference);
        ASSERT_TRUE(source.ok()) << source.error().message;
        auto variant = asset::loadGltf(v.file);
        ASSERT_TRUE(variant.ok()) << variant.error().message;
        EXPECT_TRUE(variant->warnings.empty()) << v.name << ": " << variant->warnings.front();
        expectDeformsLike(*source, *variant, v.name, kQuantisationStep, v.tool.restOnly);
    }
}

TEST_F(Variants, ToolsWriteTheExtensionsTheyAreMeantToExercise) {
    // Without this, a tool that stopped compressing would make the other tests vacuous.
    std::map<std::string, std::string> expected = {
        {"gt-draco", "KHR_draco_mesh_compression"}, {"gt-meshopt", "EXT_meshopt_compression"},
        {"gt-quantize", "KHR_mesh_quantization"},   {"gp-meshopt", "KHR_texture_transform"},
        {"gp-fallback", "EXT_meshopt_compression"}, {"gt-webp", "EXT_texture_webp"},
        {"gp-quantize", "KHR_mesh_quantization"}};
    for (const Variant& v : variants(Precision::Default)) {
        std::ifstream in(v.file, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        const std::string tool = v.name.substr(v.name.find('.') + 1);
        if (tool == "gp-meshopt" && v.source->textured == false)
            continue; // no texture coordinates to transform
        EXPECT_NE(bytes.find(expected.at(tool)), std::string::npos) << v.name;
    }
}

TEST_F(Variants, FramesMatchTheirSourcesGoldens) {
    const fs::path out = outDir();
    int compared = 0;
    for (const Variant& v : variants(Precision::Default)) {
        SCOPED_TRACE(v.name);
        const fs::path golden = fs::path(GLASS_SOURCE_DIR) / "tests/golden";
        std::ifstream in(golden / (v.source->goldenCase + ".json"));
        nlohmann::json c = nlohmann::json::parse(in);
        // The source's case, rendering the variant, beside copies of the source's goldens.
        c["model"] = fs::absolute(v.file).string();
        // Stated tolerance: at most 0.1% of the pixels more than 24 levels off (edges moved by
        // quantisation); 0.5% for glass, whose refraction bends a sub-step change of a refined,
        // deforming surface into a visible shift at silhouettes and total internal reflection.
        c["tolerance"] = {{"max_abs_diff", 24},
                          {"max_failing_fraction", c.contains("refraction") ? 0.005 : 0.001}};
        const fs::path dir = out / "cases" / v.name;
        fs::create_directories(dir);
        std::ofstream(dir / (v.source->goldenCase + ".json")) << c.dump(2);
        for (const auto& entry : fs::directory_iterator(golden))
            if (entry.path().extension() == ".png" &&
                entry.path().filename().string().rfind(v.source->goldenCase + ".t", 0) == 0)
                fs::copy_file(entry.path(), dir / entry.path().filename(),
                              fs::copy_options::overwrite_existing);
        std::string output;
        const int status = test::runCommand(std::string(GLASS_BIN_DIR) + "/glass-capture --case " +
                                                (dir / (v.source->goldenCase + ".json")).string() +
                                                " --out " + (dir / "frames").string(),
                                            &output);
        EXPECT_EQ(status, 0) << output;
        std::printf("%s: %s", v.name.c_str(), output.c_str()); // the figures, for docs/performance.md
        ++compared;
    }
    EXPECT_GE(compared, 5);
}

/** The Khronos variants in ../shared/assets/khronos against the samples they were made from. */
TEST_F(Variants, KhronosCompressedAndQuantizedSamplesDeformLikeTheirSources) {
    GLASS_REQUIRE_SHARED();
    const fs::path khronos = test::sharedDir() / "assets/khronos";
    const fs::path gltf = test::sharedDir() / "assets/gltf";
    const std::pair<const char*, const char*> pairs[] = {
        {"CesiumMan/glTF-Draco/CesiumMan.gltf", "CesiumMan/CesiumMan.glb"},
        {"RiggedSimple/glTF-Draco/RiggedSimple.gltf", "RiggedSimple/RiggedSimple.glb"},
        {"MorphPrimitivesTest/glTF-Draco/MorphPrimitivesTest.gltf",
         "MorphPrimitivesTest/MorphPrimitivesTest.glb"},
        {"AnimatedMorphCube/glTF-Quantized/AnimatedMorphCube.gltf",
         "AnimatedMorphCube/AnimatedMorphCube.glb"}};
    for (const auto& [variantFile, sourceFile] : pairs) {
        SCOPED_TRACE(variantFile);
        auto variant = asset::loadGltf(khronos / variantFile);
        ASSERT_TRUE(variant.ok()) << variant.error().message;
        auto source = asset::loadGltf(gltf / sourceFile);
        ASSERT_TRUE(source.ok()) << source.error().message;
        // How these were encoded is not recorded in them. Measured: at most 3.6e-4 of the
        // diagonal (Draco files) and 7.7e-4 (AnimatedMorphCube); 2^-10 of the diagonal is 2 mm
        // on a 2 m character.
        expectDeformsLike(*source, *variant, variantFile, 1.0 / 1024.0);
    }
}

/** Every file in ../shared/assets/khronos (Draco skinned and morph, quantized, texture transform,
 *  unlit, every primitive mode, the material test models) loads and renders through the renderer
 *  without a GL error (the fixture fails on any), and shows: its frames differ from the sky alone
 *  (the same camera with the characters out of view) over a share of the image.
 * TextureTransformTest and UnlitTest also have goldens. */
TEST_F(Variants, EveryKhronosVariantRenders) {
    // Every Khronos variant as shipped (Draco, quantized, meshopt, texture transforms, ...)
    // shows its model at two times, and shows it as the reference does (the same loaded world
    // traced by Embree, every mesh opaque as this renderer without the glass plugin draws it):
    // a model missing, black or wrongly decoded on the GPU falls far below.
    GLASS_REQUIRE_SHARED();
    auto renderer = render::Renderer::create(render::Environment::proceduralSky(16), context());
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    render::RenderSettings settings;
    settings.size = {64, 64};
    settings.hdrOutput = true;
    auto opaque = refraction::createPlugin()->parameters();
    ASSERT_TRUE(opaque.set("method", "opaque").ok());
    int rendered = 0;
    for (const auto& entry :
         fs::recursive_directory_iterator(test::sharedDir() / "assets/khronos")) {
        const auto extension = entry.path().extension();
        if (extension != ".gltf" && extension != ".glb")
            continue;
        SCOPED_TRACE(entry.path().string());
        auto world = render::loadWorld(std::vector<std::string>{entry.path().string()});
        ASSERT_TRUE(world.ok()) << world.error().message;
        const render::Camera camera = render::frameBounds(render::worldBounds(*world), 1.0f);
        auto frame = [&](double time) {
            auto stats = (*renderer)->render(*world, camera, settings, time);
            EXPECT_TRUE(stats.ok()) << (stats.ok() ? "" : stats.error().message);
            return (*renderer)->readHdrOutput();
        };
        const std::vector<std::vector<float>> frames = {frame(0.0), frame(0.6)};
        refraction::ReferenceOptions options;
        options.samplesPerPixel = 4;
        const auto traced = refraction::traceReference(
            *world, 0.0, camera,
            refraction::EnvironmentSampler::fromGpu((*renderer)->environment(), 0.0f, 1.0f),
            settings, (*renderer)->ground(), opaque, options);
        ASSERT_TRUE(traced.ok()) << traced.error().message;
        for (scene::Character& c : world->characters)
            c.placement.translation.x += 1.0e4;
        const std::vector<float> sky = frame(0.0);
        auto shows = [&](const std::vector<float>& image, std::size_t px) {
            return std::abs(image[px] - sky[px]) + std::abs(image[px + 1] - sky[px + 1]) +
                       std::abs(image[px + 2] - sky[px + 2]) >
                   0.03f;
        };
        std::vector<bool> model(sky.size() / 4); // where the GPU or the reference shows it
        for (std::size_t px = 0; px < sky.size(); px += 4)
            model[px / 4] = shows(frames[0], px) || shows(traced->rgba, px);
        const double psnr =
            capture::score({64, 64, render::cpu::tonemap(frames[0], 1.0f)},
                           {64, 64, render::cpu::tonemap(traced->rgba, 1.0f)}, &model)
                .psnr;
        // The light the model sends, on the GPU over the reference's (1: as bright).
        double gpuLight = 0.0, referenceLight = 0.0;
        for (std::size_t px = 0; px < sky.size(); px += 4)
            for (std::size_t c = 0; model[px / 4] && c < 3; ++c) {
                gpuLight += frames[0][px + c];
                referenceLight += traced->rgba[px + c];
            }
        const double brightness = gpuLight / std::max(referenceLight, 1e-9);
        for (const auto& image : frames) {
            ASSERT_EQ(image.size(), sky.size());
            std::size_t shown = 0;
            for (std::size_t px = 0; px < sky.size(); px += 4)
                shown += shows(image, px);
            std::printf("%s: %zu of %zu pixels show the model; against the reference %.2f dB, "
                        "%.2f as bright\n",
                        entry.path().filename().string().c_str(), shown, sky.size() / 4, psnr,
                        brightness);
            EXPECT_GT(shown, sky.size() / 4 / 20)
                << "the model does not show"; // 9% at least, measured
        }
        // Measured: 12.5 dB (LightsPunctualLamp, aliased at 64x64) to 36.5, 0.89 to 1.08 as
        // bright; a black model, 4-8 dB and 0.
        EXPECT_GE(psnr, 10.0) << "the model does not show as the reference shows it";
        EXPECT_NEAR(brightness, 1.0, 0.25) << "the model is not as bright as the reference's";
        ++rendered;
    }
    EXPECT_GE(rendered, 7);
}

/** TextureTransformTest's lower planes hold an arrow (Arrow.png rotated, scaled, or both, by
 *  KHR_texture_transform) and small marks: "Correct" (green) where the arrow points when the
 *  transform is right, "Not supported" (olive) where it points without the extension, "Error"
 *  (red) where a wrong transform points. Every green mark must touch the arrow's dark pixels and
 *  lie closer to them than any other mark. (Correct.png is that green mark's texture, not a
 *  picture of the whole scene.) */
TEST_F(Variants, TextureTransformTestArrowsPointAtTheCorrectMarks) {
    GLASS_REQUIRE_SHARED();
    test::TempDir dir;
    std::string out;
    ASSERT_EQ(test::runCommand(std::string(GLASS_BIN_DIR) + "/glass-capture " +
                                   (test::sharedDir() / "assets/khronos/TextureTransformTest/glTF/"
                                                        "TextureTransformTest.gltf")
                                       .string() +
                                   " --size 512x384 --out " + dir.path().string(),
                               &out),
              0)
        << out;
    auto image = capture::readPng(dir / "TextureTransformTest_rest_t0.000.png");
    ASSERT_TRUE(image.ok()) << image.error().message;
    const int w = image->width, h = image->height;
    auto rgb = [&](int x, int y) {
        const std::uint8_t* p =
            &image->rgba[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
        return glm::ivec3(p[0], p[1], p[2]);
    };
    // The lower half: the three arrow planes (the upper row is the offset planes).
    std::vector<glm::vec2> dark;
    std::map<std::string, std::vector<glm::vec2>> marks;
    for (int y = h / 2; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::ivec3 c = rgb(x, y);
            const glm::vec2 at(x, y);
            if (c.r + c.g + c.b < 120)
                dark.push_back(at);
            else if (c.g > 100 && c.g > c.r + 50 && c.g > c.b + 50)
                marks["correct"].push_back(at);
            else if (c.r > 120 && c.r > c.g + 60 && c.r > c.b + 60)
                marks["error"].push_back(at);
            else if (c.r > 90 && c.g > 90 && c.b + 50 < std::min(c.r, c.g))
                marks["not supported"].push_back(at);
        }
    ASSERT_GT(dark.size(), 100u) << "no arrows";
    ASSERT_GT(marks["correct"].size(), 30u) << "no Correct marks";
    // Each mark's pixels in clusters (a mark is a few pixels across); per cluster, the distance
    // from its nearest pixel to the nearest arrow pixel.
    auto distances = [&](const std::vector<glm::vec2>& pixels) {
        std::vector<std::vector<glm::vec2>> clusters;
        for (const glm::vec2& p : pixels) {
            auto it = std::find_if(clusters.begin(), clusters.end(), [&](const auto& c) {
                return glm::distance(c.front(), p) < 20.0f;
            });
            if (it == clusters.end())
                clusters.push_back({p});
            else
                it->push_back(p);
        }
        std::vector<float> nearestArrow;
        for (const auto& cluster : clusters) {
            float nearest = 1e9f;
            for (const glm::vec2& p : cluster)
                for (const glm::vec2& d : dark)
                    nearest = std::min(nearest, glm::distance(p, d));
            nearestArrow.push_back(nearest);
        }
        return nearestArrow;
    };
    const std::vector<float> correct = distances(marks["correct"]);
    EXPECT_EQ(correct.size(), 3u) << "one Correct mark on each arrow plane";
    const float farthestCorrect = *std::max_element(correct.begin(), correct.end());
    // Measured: 3 to 6 pixels (the mark's white rim), the other marks 22 to 33 pixels away.
    EXPECT_LE(farthestCorrect, 10.0f) << "an arrow misses its Correct mark";
    for (const char* other : {"error", "not supported"})
        for (float d : distances(marks[other]))
            EXPECT_GT(d, farthestCorrect) << "an arrow points at a mark for " << other;
}

} // namespace
