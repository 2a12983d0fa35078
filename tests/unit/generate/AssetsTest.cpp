// The project's generated default assets: they are what the generator writes (byte for byte),
// they load, they have what the default character must have, and the Khronos glTF-Validator
// finds no error and no warning in them.
#include "Figure.h"
#include "Sky.h"
#include "support/TestSupport.h"

#include "engine/asset/HdrImage.h"
#include "engine/asset/ModelLoader.h"
#include "engine/core/Files.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace {

const std::filesystem::path kAssets = std::filesystem::path(GLASS_SOURCE_DIR) / "assets";
const std::filesystem::path kFigure = kAssets / "models" / "glass_figure.glb";
const std::filesystem::path kParts = kAssets / "models" / "glass_figure_parts.glb";
const std::filesystem::path kSky = kAssets / "env" / "sunset_sky.hdr";

std::vector<std::uint8_t> bytesOf(const std::filesystem::path& path) {
    auto bytes = core::readFile(path);
    EXPECT_TRUE(bytes.ok()) << path;
    return bytes.ok() ? *bytes : std::vector<std::uint8_t>{};
}

TEST(GeneratedAssets, CommittedFilesAreTheGeneratorsOutput) {
    EXPECT_TRUE(bytesOf(kFigure) == generate::buildFigureGlb())
        << "assets/models/glass_figure.glb is stale: run build/bin/glass-generate-assets --force";
    EXPECT_TRUE(bytesOf(kParts) == generate::buildFigureGlb({.parts = true}))
        << "assets/models/glass_figure_parts.glb is stale: run build/bin/glass-generate-assets "
           "--force";
    EXPECT_TRUE(bytesOf(kSky) == asset::encodeHdr(generate::buildSky()))
        << "assets/env/sunset_sky.hdr is stale: run build/bin/glass-generate-assets --force";
}

TEST(GeneratedAssets, TheFigureIsASkinnedMorphingAnimatedGlassCharacter) {
    auto model = asset::loadModel(kFigure.string());
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->skins.size(), 1u);
    EXPECT_GE(model->skins[0].joints.size(), 15u);
    ASSERT_EQ(model->meshes.size(), 1u);
    for (const auto& primitive : model->meshes[0].primitives)
        EXPECT_GE(primitive.targets.size(), 1u);
    std::vector<std::string> clips;
    for (const auto& clip : model->animations)
        clips.push_back(clip.name);
    EXPECT_EQ(clips, (std::vector<std::string>{"walk", "wave", "idle", "stroll"}));
    const scene::Material& glass = model->materials.at(0);
    EXPECT_TRUE(glass.isTransmissive());
    EXPECT_FLOAT_EQ(glass.transmissionFactor, 1.0f);
    EXPECT_FLOAT_EQ(glass.ior, 1.5f);
    EXPECT_GT(glass.dispersion, 0.0f);
    EXPECT_GT(glass.thicknessFactor, 0.0f);
    // Watertight and smooth: every edge of the glass body is shared by exactly two triangles.
    const auto& body = model->meshes[0].primitives[0];
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (std::size_t t = 0; t < body.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = body.indices[t + std::size_t(k)];
            const std::uint32_t b = body.indices[t + std::size_t((k + 1) % 3)];
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    std::size_t open = 0;
    for (const auto& [edge, count] : edges)
        open += count != 2;
    EXPECT_EQ(open, 0u) << "edges not shared by exactly two triangles";
}

TEST(GeneratedAssets, ThePartsFigureHasAGlassPerPartAndANormalMappedHead) {
    auto model = asset::loadModel(kParts.string());
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->skins.size(), 1u);
    ASSERT_EQ(model->meshes.size(), 1u);
    std::set<float> iors;
    int mapped = 0;
    for (const auto& primitive : model->meshes[0].primitives) {
        const scene::Material& m = model->materials.at(std::size_t(primitive.material));
        if (!m.isTransmissive())
            continue;
        iors.insert(m.ior);
        if (m.normalTexture.present()) {
            ++mapped;
            EXPECT_FALSE(primitive.uv0.empty());
            EXPECT_FALSE(primitive.tangents.empty());
        }
    }
    EXPECT_GE(iors.size(), 4u) << "a glass of its own per part";
    EXPECT_EQ(mapped, 1);
}

TEST(GeneratedAssets, TheSkyLoadsAsAnEnvironment) {
    auto sky = asset::loadHdr(kSky);
    ASSERT_TRUE(sky.ok()) << sky.error().message;
    EXPECT_EQ(sky->width, 2 * sky->height);
    float brightest = 0.0f;
    for (float v : sky->rgb)
        brightest = std::max(brightest, v);
    EXPECT_GT(brightest, 20.0f) << "the sun";
}

TEST(GeneratedAssets, KhronosValidatorFindsNoErrorOrWarning) {
    const std::string modules =
        std::getenv("GLASS_VALIDATOR_MODULES")
            ? std::getenv("GLASS_VALIDATOR_MODULES")
            : std::string(GLASS_SOURCE_DIR) + "/build/validator/node_modules";
    const std::string script = std::string(GLASS_SOURCE_DIR) + "/tests/validator/validate.mjs";
    if (test::runCommand("command -v node >/dev/null") != 0)
        GTEST_SKIP() << "node is missing (scripts/deps installs Node.js)";
    std::string out;
    int status = 0;
    for (const auto& file : {kFigure, kParts}) {
        status = test::runCommand("node " + script + " " + modules + " " + file.string(), &out);
        if (status == 77)
            GTEST_SKIP() << out;
        EXPECT_EQ(status, 0) << out;
        EXPECT_NE(out.find("0 errors, 0 warnings"), std::string::npos) << out;
    }
    // The harness can fail: a file with a bad accessor reference is reported.
    test::TempDir dir;
    test::GltfBuilder broken = test::twoJointModel();
    broken.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 99;
    const auto path = broken.save(dir.path(), "broken", test::GltfFormat::Glb);
    status = test::runCommand("node " + script + " " + modules + " " + path.string(), &out);
    EXPECT_EQ(status, 1) << out;
    EXPECT_NE(out.find("error"), std::string::npos) << out;
}

} // namespace
