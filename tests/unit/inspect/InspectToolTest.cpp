// glass-inspect as a user runs it: exit codes, JSON keys and counts, PLY output.
#include "support/TestSupport.h"

#include "engine/anim/Pose.h"
#include "engine/asset/GltfLoader.h"
#include "engine/asset/SceneFile.h"
#include "engine/capture/Image.h"
#include "engine/deform/CpuDeformer.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

namespace {

const std::string kInspect = std::string(GLASS_BIN_DIR) + "/glass-inspect";

struct Ply {
    std::size_t count = 0;
    std::vector<float> values; // 6 per vertex
};

Ply readPly(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    Ply ply;
    std::string line;
    bool ascii = false;
    while (std::getline(in, line) && line != "end_header") {
        if (line.rfind("element vertex ", 0) == 0)
            ply.count = std::stoul(line.substr(15));
        if (line == "format ascii 1.0")
            ascii = true;
    }
    ply.values.resize(ply.count * 6);
    if (ascii)
        for (float& v : ply.values)
            in >> v;
    else
        in.read(reinterpret_cast<char*>(ply.values.data()), std::streamsize(ply.values.size() * 4));
    return ply;
}

TEST(InspectTool, ExitCodes) {
    std::string out;
    EXPECT_EQ(test::runCommand(kInspect + " --help", &out), 0);
    EXPECT_NE(out.find("PLY layout"), std::string::npos);
    EXPECT_EQ(test::runCommand(kInspect, &out), 2);
    EXPECT_EQ(test::runCommand(kInspect + " model.glb --bogus", &out), 2);
    EXPECT_NE(out.find("unknown option --bogus"), std::string::npos);
    EXPECT_EQ(test::runCommand(kInspect + " model.glb --time -3 --vertices cpu --out x.ply", &out),
              2);
    EXPECT_EQ(test::runCommand(kInspect + " model.glb --vertices cpu", &out), 2);
}

TEST(InspectTool, BadModelExitsOneAndWritesNothing) {
    test::TempDir dir;
    test::GltfBuilder broken = test::twoJointModel();
    broken.doc["skins"][0]["joints"][0] = 40;
    const auto path = broken.save(dir.path(), "broken");
    std::string out;
    const std::string ply = (dir / "out.ply").string();
    EXPECT_EQ(
        test::runCommand(kInspect + " " + path.string() + " --vertices cpu --out " + ply, &out), 1);
    EXPECT_NE(out.find("broken.gltf: skin 0: joint 0 references node 40, file has 3 nodes"),
              std::string::npos)
        << out;
    EXPECT_FALSE(std::filesystem::exists(ply));
}

TEST(InspectTool, JsonDescribesTheModel) {
    test::TempDir dir;
    const auto path = test::twoJointModel().save(dir.path(), "twojoint", test::GltfFormat::Glb);
    std::string out;
    ASSERT_EQ(test::runCommand("(" + kInspect + " " + path.string() + " --json 2>/dev/null)", &out),
              0)
        << out;
    const auto j = nlohmann::json::parse(out);
    EXPECT_EQ(j["meshes"], 1);
    EXPECT_EQ(j["primitives"], 1);
    EXPECT_EQ(j["triangles"], 4);
    EXPECT_EQ(j["vertices"], 6);
    EXPECT_EQ(j["skins"], 1);
    EXPECT_EQ(j["joints_per_skin"], nlohmann::json::array({2}));
    EXPECT_EQ(j["max_morph_targets"], 1);
    EXPECT_EQ(j["animations"], 1);
    EXPECT_EQ(j["animation_list"][0]["name"], "bend");
    EXPECT_EQ(j["animation_list"][0]["interpolation"], nlohmann::json::array({"LINEAR"}));
    EXPECT_DOUBLE_EQ(j["animation_list"][0]["duration_s"].get<double>(), 1.0);
    ASSERT_EQ(test::runCommand(kInspect + " " + path.string(), &out), 0);
    EXPECT_NE(out.find("clip 'bend': 1.000 s"), std::string::npos) << out;
}

TEST(InspectTool, ListsEachPointerChannelAsPlayedOrSkipped) {
    test::TempDir dir;
    const auto path = test::pointerTwoJointModel().save(dir.path(), "pointers");
    std::string out;
    ASSERT_EQ(test::runCommand(kInspect + " " + path.string() + " 2>&1", &out), 0) << out;
    for (const char* line : {"channel 0: KHR_animation_pointer /nodes/2/rotation, played",
                             "channel 1: KHR_animation_pointer /nodes/0/weights, played",
                             "channel 2: KHR_animation_pointer "
                             "/materials/0/pbrMetallicRoughness/metallicFactor, played",
                             "channel 3: KHR_animation_pointer /materials/0/alphaCutoff, skipped",
                             "channel 4: KHR_animation_pointer "
                             "/extensions/KHR_lights_punctual/lights/0/intensity, played",
                             "channel 7: KHR_animation_pointer /materials/0/pbrMetallicRoughness/"
                             "baseColorTexture/extensions/KHR_texture_transform/offset, played",
                             "channel 8: KHR_animation_pointer /cameras/0/perspective/yfov, "
                             "played"})
        EXPECT_NE(out.find(line), std::string::npos) << line << " in\n" << out;
    ASSERT_EQ(test::runCommand("(" + kInspect + " " + path.string() + " --json 2>/dev/null)", &out),
              0);
    const auto pointers = nlohmann::json::parse(out)["animation_list"][0]["pointer_channels"];
    ASSERT_EQ(pointers.size(), 9u);
    EXPECT_EQ(pointers[3]["played"], false);
    EXPECT_EQ(pointers[8]["played"], true);
}

TEST(InspectTool, JsonMatchesInventoryForSharedCharacters) {
    GLASS_REQUIRE_SHARED();
    std::ifstream in(test::sharedDir() / "assets/INVENTORY.json");
    const auto inventory = nlohmann::json::parse(in);
    for (const auto& expected : inventory["models"]) {
        const auto path = test::sharedDir() / "assets" / expected["file"].get<std::string>();
        std::string out;
        ASSERT_EQ(
            test::runCommand("(" + kInspect + " " + path.string() + " --json 2>/dev/null)", &out),
            0)
            << out;
        const auto j = nlohmann::json::parse(out);
        SCOPED_TRACE(expected["name"].get<std::string>());
        for (const char* key : {"meshes", "primitives", "triangles", "vertices", "skins",
                                "joints_per_skin", "max_morph_targets", "animations"})
            EXPECT_EQ(j[key], expected[key]) << key;
        ASSERT_EQ(j["animation_list"].size(), expected["animation_list"].size());
        for (std::size_t a = 0; a < j["animation_list"].size(); ++a) {
            EXPECT_EQ(j["animation_list"][a]["name"], expected["animation_list"][a]["name"]);
            EXPECT_EQ(j["animation_list"][a]["interpolation"],
                      expected["animation_list"][a]["interpolation"]);
            EXPECT_NEAR(j["animation_list"][a]["duration_s"].get<double>(),
                        expected["animation_list"][a]["duration_s"].get<double>(), 5e-4);
        }
    }
}

TEST(InspectTool, PlyHoldsTheCpuDeformation) {
    test::TempDir dir;
    test::GltfBuilder builder = test::twoJointModel();
    builder.doc["nodes"][0]["translation"] = {0.0, 0.0, 3.0}; // skinned: ignored, as glTF says
    const auto path = builder.save(dir.path(), "twojoint");
    for (const char* format : {"", " --ascii"}) {
        const auto ply = dir / "out.ply";
        std::string out;
        // The second format replaces the first one's file: --force.
        ASSERT_EQ(test::runCommand(kInspect + " " + path.string() +
                                       " --vertices cpu --time 1 --clip bend --force --out " +
                                       ply.string() + format,
                                   &out),
                  0)
            << out;
        const Ply result = readPly(ply);
        ASSERT_EQ(result.count, 6u);
        // Vertex 2 at t = 1 is at (1,1,1) (see CpuDeformerTest), normal +z.
        EXPECT_NEAR(result.values[2 * 6 + 0], 1.0f, 1e-5f);
        EXPECT_NEAR(result.values[2 * 6 + 1], 1.0f, 1e-5f);
        EXPECT_NEAR(result.values[2 * 6 + 2], 1.0f, 1e-5f);
        EXPECT_NEAR(result.values[2 * 6 + 5], 1.0f, 1e-5f);
    }
    std::string out;
    EXPECT_EQ(test::runCommand(kInspect + " " + path.string() +
                                   " --vertices cpu --clip nope --out " + (dir / "x.ply").string(),
                               &out),
              2);
    EXPECT_FALSE(std::filesystem::exists(dir / "x.ply"));
}

/** `glass-inspect ARGUMENTS --vertices cpu|gpu` into DIR/cpu.ply and DIR/gpu.ply. */
struct PlyPair {
    bool noContext = false; ///< no headless OpenGL here: the GPU side could not run
    std::string output;
    Ply cpu, gpu;
};
PlyPair cpuAndGpuPly(const std::string& arguments, const test::TempDir& dir) {
    PlyPair pair;
    const std::string base = kInspect + " " + arguments + " --out ";
    EXPECT_EQ(test::runCommand(base + (dir / "cpu.ply").string() + " --vertices cpu", &pair.output),
              0)
        << pair.output;
    const int gpuStatus =
        test::runCommand(base + (dir / "gpu.ply").string() + " --vertices gpu", &pair.output);
    pair.noContext = gpuStatus != 0 && pair.output.find("no headless OpenGL") != std::string::npos;
    if (!pair.noContext) {
        EXPECT_EQ(gpuStatus, 0) << pair.output;
    }
    pair.cpu = readPly(dir / "cpu.ply");
    pair.gpu = readPly(dir / "gpu.ply");
    return pair;
}

TEST(InspectTool, GpuPlyMatchesCpuPly) {
    test::TempDir dir;
    const auto path = test::twoJointModel().save(dir.path(), "twojoint");
    const PlyPair pair = cpuAndGpuPly(path.string() + " --time 0.6", dir);
    if (pair.noContext)
        GTEST_SKIP() << pair.output;
    const Ply &cpu = pair.cpu, &gpu = pair.gpu;
    ASSERT_EQ(cpu.count, gpu.count);
    for (std::size_t i = 0; i < cpu.values.size(); ++i)
        EXPECT_NEAR(cpu.values[i], gpu.values[i], 1e-5f) << i;
}

TEST(InspectTool, SceneCharactersDeformOnTheGpuAsTheCpuOracleSays) {
    test::TempDir dir;
    test::twoJointModel().save(dir.path(), "twojoint", test::GltfFormat::Glb);
    // Two characters of one model at other times, speeds and transforms.
    const nlohmann::json scene = {
        {"characters",
         {{{"model", "twojoint.glb"}, {"translation", {-2, 0, 0}}, {"time_offset", 0.1}},
          {{"model", "twojoint.glb"},
           {"translation", {2, 1, 0}},
           {"rotation", {0, 0.7071068, 0, 0.7071068}},
           {"scale", {1.5, 1.5, 1.5}},
           {"time_offset", 0.35},
           {"speed", 1.4}}}}};
    const auto scenePath = dir / "pair.json";
    std::ofstream(scenePath) << scene.dump();
    const PlyPair pair = cpuAndGpuPly(scenePath.string() + " --time 0.2", dir);
    if (pair.noContext)
        GTEST_SKIP() << pair.output;
    const Ply &cpu = pair.cpu, &gpu = pair.gpu;
    // The oracle: each character deformed on the CPU and placed, in the scene's order.
    const auto world = asset::loadScene(scenePath);
    ASSERT_TRUE(world.ok()) << world.error().message;
    std::vector<float> oracle;
    for (const scene::Character& c : world->characters)
        for (const auto& instance : deform::deformCharacter(c, 0.2))
            for (const auto& primitive : instance.primitives) {
                const auto placed = deform::toWorld(primitive, instance.meshToWorld);
                for (std::size_t v = 0; v < placed.positions.size(); ++v)
                    for (const glm::dvec3& x : {placed.positions[v], placed.normals[v]})
                        oracle.insert(oracle.end(), {float(x.x), float(x.y), float(x.z)});
            }
    ASSERT_EQ(cpu.count * 6, oracle.size());
    ASSERT_EQ(gpu.count, cpu.count);
    for (std::size_t i = 0; i < oracle.size(); ++i) {
        EXPECT_NEAR(cpu.values[i], oracle[i], 1e-5f) << i;
        EXPECT_NEAR(gpu.values[i], oracle[i], 1e-4f) << i;
    }
    // Not vacuous: the second character is not the first one moved (other time, rotation).
    const std::size_t half = cpu.count / 2;
    double differs = 0.0;
    for (std::size_t v = 0; v < half; ++v) {
        const glm::dvec3 a(cpu.values[6 * v], cpu.values[6 * v + 1], cpu.values[6 * v + 2]);
        const glm::dvec3 b(cpu.values[6 * (v + half)], cpu.values[6 * (v + half) + 1],
                           cpu.values[6 * (v + half) + 2]);
        differs = std::max(
            differs, glm::length((b - glm::dvec3(2, 1, 0)) / 1.5 - (a - glm::dvec3(-2, 0, 0))));
    }
    EXPECT_GT(differs, 1e-2);
}

TEST(InspectTool, SeveralModelsAreAWorldSideBySide) {
    test::TempDir dir;
    const auto model = test::twoJointModel().save(dir.path(), "twojoint").string();
    std::string out;
    ASSERT_EQ(
        test::runCommand(kInspect + " " + model + " builtin:sphere?segments=16 " + model, &out), 0)
        << out;
    EXPECT_NE(out.find("characters 3, models 2"), std::string::npos) << out;
    // Their vertices, CPU and GPU alike, each character placed apart from the one before.
    const PlyPair pair = cpuAndGpuPly(model + " " + model + " --time 0.3", dir);
    if (pair.noContext)
        GTEST_SKIP() << pair.output;
    ASSERT_EQ(pair.cpu.count, pair.gpu.count);
    for (std::size_t i = 0; i < pair.cpu.values.size(); ++i)
        EXPECT_NEAR(pair.cpu.values[i], pair.gpu.values[i], 1e-4f) << i;
    const std::size_t half = pair.cpu.count / 2;
    float firstMax = -1e30f, secondMin = 1e30f;
    for (std::size_t v = 0; v < half; ++v) {
        firstMax = std::max(firstMax, pair.cpu.values[6 * v]);
        secondMin = std::min(secondMin, pair.cpu.values[6 * (v + half)]);
    }
    EXPECT_LT(firstMax, secondMin) << "the second stands right of the first";
    EXPECT_EQ(test::runCommand(kInspect + " " + model + " " + model + " --clip bend", &out), 2);
}

TEST(InspectTool, CheckListsEveryFileAndFailsOnARefusal) {
    test::TempDir dir;
    std::filesystem::create_directories(dir / "sub");
    test::twoJointModel().save(dir.path(), "good", test::GltfFormat::Glb);
    test::GltfBuilder used = test::twoJointModel();
    used.doc["extensionsUsed"] = {"KHR_materials_diffuse_transmission"};
    used.save(dir.path() / "sub", "used");
    std::string out;
    ASSERT_EQ(test::runCommand(kInspect + " --check " + dir.path().string(), &out), 0) << out;
    EXPECT_NE(out.find("ok       " + (dir / "good.glb").string()), std::string::npos) << out;
    EXPECT_NE(out.find("warnings " + (dir / "sub" / "used.gltf").string() +
                       ": extensionsUsed lists KHR_materials_diffuse_transmission"),
              std::string::npos)
        << out;
    test::GltfBuilder required = test::twoJointModel();
    required.doc["extensionsUsed"] = {"KHR_gaussian_splatting"};
    required.doc["extensionsRequired"] = {"KHR_gaussian_splatting"};
    required.save(dir.path() / "sub", "required");
    EXPECT_EQ(test::runCommand(kInspect + " --check " + dir.path().string(), &out), 1) << out;
    EXPECT_NE(out.find("refused  " + (dir / "sub" / "required.gltf").string() +
                       ": asset::loadGltf(): required.gltf: extensionsRequired lists "
                       "KHR_gaussian_splatting"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("3 files: 1 ok, 1 ok with warnings, 1 refused"), std::string::npos) << out;
    EXPECT_EQ(test::runCommand(kInspect + " --check " + (dir / "nothing").string(), &out), 2);
}

TEST(InspectTool, CheckOverTheSharedAssets) {
    GLASS_REQUIRE_SHARED();
    const auto root = test::sharedDir() / "assets";
    std::string out;
    const int status = test::runCommand(kInspect + " --check " + root.string(), &out);
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        const auto extension = entry.path().extension();
        if (entry.is_regular_file() && (extension == ".gltf" || extension == ".glb")) {
            ++files;
            // (appended in steps: `" " + path.string()` trips GCC 12's -Wrestrict false
            // positive at -O3, GCC bug 105329)
            std::string line = " ";
            line += entry.path().string();
            EXPECT_NE(out.find(line), std::string::npos) << entry.path() << " has no line";
        }
    }
    EXPECT_NE(out.find(std::to_string(files) + " files: "), std::string::npos) << out;
    // Every shared file loads: Draco, quantized, texture transform, unlit and every primitive
    // mode (POINTS and LINES are skipped with a warning) included.
    EXPECT_EQ(out.find("refused  "), std::string::npos) << out;
    EXPECT_EQ(status, 0) << out;
}

TEST(InspectTool, BadSceneExitsOneNamingTheKeyAndWritesNothing) {
    test::TempDir dir;
    test::twoJointModel().save(dir.path(), "twojoint", test::GltfFormat::Glb);
    const auto scenePath = dir / "crowd.json";
    std::ofstream(scenePath)
        << R"({"characters": [{"model": "twojoint.glb"}, {"model": "twojoint.glb", "clip": "Jump"}]})";
    std::string out;
    const auto ply = dir / "out.ply";
    EXPECT_EQ(test::runCommand(kInspect + " " + scenePath.string() + " --vertices cpu --out " +
                                   ply.string(),
                               &out),
              1);
    EXPECT_NE(
        out.find("crowd.json: characters[1].clip: \"Jump\" not in twojoint.glb (clips: bend)"),
        std::string::npos)
        << out;
    EXPECT_FALSE(std::filesystem::exists(ply));
    EXPECT_EQ(test::runCommand(kInspect + " " + scenePath.string() + " --clip bend", &out), 2);
}

TEST(InspectTool, CesiumManPlyHasEveryVertex) {
    GLASS_REQUIRE_SHARED();
    test::TempDir dir;
    const auto model = test::sharedDir() / "assets/gltf/CesiumMan/CesiumMan.glb";
    std::string out;
    ASSERT_EQ(test::runCommand(kInspect + " " + model.string() +
                                   " --vertices cpu --time 1.0 --out " +
                                   (dir / "cesium.ply").string(),
                               &out),
              0)
        << out;
    const Ply ply = readPly(dir / "cesium.ply");
    EXPECT_EQ(ply.count, 3273u);
    const auto loaded = asset::loadGltf(model);
    ASSERT_TRUE(loaded.ok());
    const auto instances = deform::deformScene(*loaded, anim::evaluate(*loaded, 0, 1.0));
    const auto world = deform::toWorld(instances[0].primitives[0], instances[0].meshToWorld);
    for (std::size_t v = 0; v < ply.count; v += 97)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(ply.values[v * 6 + std::size_t(c)], float(world.positions[v][c]), 1e-5f);
}

} // namespace

namespace {

const std::string kCompare = std::string(GLASS_BIN_DIR) + "/glass-compare";

TEST(CompareTool, ScoresTwoImagesOverAMask) {
    test::TempDir dir;
    capture::Image a{16, 16, std::vector<std::uint8_t>(std::size_t(16 * 16 * 4), 100)};
    capture::Image b = a;
    for (int i = 0; i < 16; ++i)
        b.rgba[std::size_t(i) * 4] = 140; // first row differs
    capture::Image mask{16, 16, std::vector<std::uint8_t>(std::size_t(16 * 16 * 4), 0)};
    for (std::size_t i = std::size_t(128); i < std::size_t(256); ++i) // the lower half
        mask.rgba[i * 4] = 255;                                       // bottom half
    ASSERT_TRUE(capture::writePng(dir / "a.png", a).ok());
    ASSERT_TRUE(capture::writePng(dir / "b.png", b).ok());
    ASSERT_TRUE(capture::writePng(dir / "m.png", mask).ok());
    std::string out;
    ASSERT_EQ(test::runCommand(kCompare + " " + (dir / "a.png").string() + " " +
                                   (dir / "b.png").string() + " --mask " +
                                   (dir / "m.png").string() + " --json --heatmap " +
                                   (dir / "h.png").string(),
                               &out),
              0)
        << out;
    const auto j = nlohmann::json::parse(out);
    EXPECT_EQ(j["mask"]["psnr"], 99.0); // the differing row is outside the mask
    EXPECT_EQ(j["mask"]["pixels"], 128);
    // One row of 16x16 off by 40 in one channel: MSE = 40^2 / (16 * 3).
    EXPECT_NEAR(j["image"]["psnr"].get<double>(), 10 * std::log10(255.0 * 255.0 * 48.0 / 1600.0),
                1e-6);
    EXPECT_TRUE(std::filesystem::exists(dir / "h.png"));
    EXPECT_EQ(test::runCommand(kCompare + " " + (dir / "a.png").string(), &out), 2);
    EXPECT_EQ(test::runCommand(kCompare + " " + (dir / "a.png").string() + " " +
                                   (dir / "nope.png").string(),
                               &out),
              1);
}

TEST(InspectTool, AnExistingPlyIsKeptWithoutForce) {
    test::TempDir dir;
    const auto path = test::twoJointModel().save(dir.path(), "twojoint");
    const auto ply = dir / "out.ply";
    std::ofstream(ply) << "keep me";
    std::string out;
    EXPECT_EQ(test::runCommand(
                  kInspect + " " + path.string() + " --vertices cpu --out " + ply.string(), &out),
              1);
    EXPECT_NE(out.find("exists (use --force to replace it)"), std::string::npos) << out;
    std::ifstream in(ply);
    const std::string kept{std::istreambuf_iterator<char>(in), {}};
    EXPECT_EQ(kept, "keep me");
}

} // namespace
