// glass-capture as a user runs it: arguments, outputs, JSON timings, case files, plugins.
#include "support/TestSupport.h"

#include "engine/capture/Image.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

namespace {

const std::string kCapture = std::string(GLASS_BIN_DIR) + "/glass-capture";
const std::string kLib = GLASS_LIB_DIR;

/** Runs glass-capture; skips the test when this machine cannot make any GL context. */
int capture(const std::string& args, std::string* out) {
    const int status = test::runCommand(kCapture + " " + args, out);
    return status;
}

#define SKIP_WITHOUT_GL(out)                                                                       \
    if ((out).find("no headless OpenGL") != std::string::npos)                                     \
    GTEST_SKIP() << (out)

TEST(CaptureTool, BadArgumentsExitTwo) {
    std::string out;
    EXPECT_EQ(capture("", &out), 2);
    EXPECT_EQ(capture("model.glb --bogus", &out), 2);
    EXPECT_NE(out.find("unknown option --bogus"), std::string::npos);
    EXPECT_EQ(capture("model.glb --size 0x5", &out), 2);
    EXPECT_EQ(capture("model.glb --size 12", &out), 2);
    EXPECT_EQ(capture("model.glb --frames 2:1:0.5", &out), 2);
    EXPECT_EQ(capture("model.glb --time 1 --frames 0:1:0.5", &out), 2);
    EXPECT_EQ(capture("model.glb --set a=b", &out), 2);
    EXPECT_EQ(capture("--help", &out), 0);
    EXPECT_EQ(capture("builtin:sphere --method magic", &out), 2);
    EXPECT_NE(
        out.find("--method: parameter 'method' takes opaque|sir|isr|dir|trace|hybrid, got 'magic'"),
        std::string::npos)
        << out;
    EXPECT_EQ(capture("builtin:sphere --ior 9", &out), 2);
    EXPECT_EQ(capture("builtin:sphere --tint 1,2", &out), 2);
    EXPECT_EQ(capture("builtin:sphere --search-steps 17", &out), 2);
    EXPECT_EQ(capture("builtin:cube", &out), 1);
    EXPECT_NE(out.find("unknown built-in model 'builtin:cube'"), std::string::npos) << out;
}

TEST(CaptureTool, BadModelExitsOneAndWritesNothing) {
    test::TempDir dir;
    test::GltfBuilder broken = test::twoJointModel();
    broken.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;
    const auto model = broken.save(dir.path(), "broken");
    std::string out;
    EXPECT_EQ(capture(model.string() + " --out " + (dir / "frames").string(), &out), 1);
    EXPECT_NE(out.find("broken.gltf: mesh 0 primitive 0 POSITION references accessor 99"),
              std::string::npos)
        << out;
    EXPECT_FALSE(std::filesystem::exists(dir / "frames"));
}

TEST(CaptureTool, JsonListsFilesTimesAndPassTimings) {
    test::TempDir dir;
    const auto model = test::twoJointModel().save(dir.path(), "twojoint");
    std::string out;
    const int status = capture(model.string() + " --frames 0:1:0.5 --size 64x48 --json --out " +
                                   (dir / "frames").string() + " 2>/dev/null",
                               &out);
    SKIP_WITHOUT_GL(out);
    ASSERT_EQ(status, 0) << out;
    const auto j = nlohmann::json::parse(out);
    ASSERT_EQ(j["frames"].size(), 3u);
    EXPECT_EQ(j["frames"][1]["time"], 0.5);
    const std::string file = j["frames"][2]["file"];
    EXPECT_NE(file.find("twojoint_bend_t1.000.png"), std::string::npos);
    auto image = capture::readPng(file);
    ASSERT_TRUE(image.ok());
    EXPECT_EQ(image->width, 64);
    EXPECT_EQ(image->height, 48);
    std::vector<std::string> passes;
    for (const auto& p : j["frames"][0]["passes"]) {
        passes.push_back(p["name"]);
        EXPECT_GE(p["cpu_ms"].get<double>(), 0.0);
        EXPECT_GE(p["gpu_ms"].get<double>(), 0.0);
    }
    EXPECT_EQ(passes, (std::vector<std::string>{"deform", "background", "opaque", "tonemap"}));
}

TEST(CaptureTool, DumpShadersWritesEveryProgramAsGivenToGl) {
    // --dump-shaders DIR: each program the frames compiled, each stage as GL got it, the
    // variant's defines and the registry's in it; a second run adds nothing.
    test::TempDir dir;
    const std::string shaders = (dir / "shaders").string();
    const std::string args = "builtin:sphere --size 32x32 --method dir --out " +
                             (dir / "frames").string() + " --force --dump-shaders " + shaders;
    std::string out;
    const int status = capture(args + " 2>&1", &out);
    SKIP_WITHOUT_GL(out);
    ASSERT_EQ(status, 0) << out;
    std::map<std::string, std::set<std::string>> stages; // program: its stages' extensions
    for (const auto& entry : std::filesystem::directory_iterator(shaders))
        stages[entry.path().stem().string()].insert(entry.path().extension().string());
    const auto named = [&](const std::string& stem) {
        return std::count_if(stages.begin(), stages.end(),
                             [&](const auto& p) { return p.first.rfind(stem + "-", 0) == 0; });
    };
    EXPECT_EQ(named("walk"), 1) << "one walk variant in a DIR frame";
    EXPECT_EQ(named("layer_capture"), 1);
    EXPECT_GE(named("deform"), 1);
    for (const auto& [program, extensions] : stages)
        EXPECT_TRUE(extensions == std::set<std::string>{".comp"} ||
                    extensions == (std::set<std::string>{".frag", ".vert"}))
            << program;
    const auto walk = std::find_if(stages.begin(), stages.end(),
                                   [](const auto& p) { return p.first.rfind("walk-", 0) == 0; });
    ASSERT_NE(walk, stages.end());
    std::ifstream in(std::filesystem::path(shaders) / (walk->first + ".frag"));
    const std::string source((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(source.rfind("#version 450 core\n", 0), 0u);
    EXPECT_NE(source.find("#define LAYER_METHOD "), std::string::npos) << "the variant's";
    EXPECT_NE(source.find("#define LAYER_HEADS_BINDING"), std::string::npos) << "the registry's";
    EXPECT_EQ(source.find("#include"), std::string::npos) << "includes expanded";
    const std::size_t files = std::distance(std::filesystem::directory_iterator(shaders), {});
    ASSERT_EQ(capture(args + " 2>&1", &out), 0) << out;
    EXPECT_EQ(std::size_t(std::distance(std::filesystem::directory_iterator(shaders), {})), files);
}

/** Writes the two-joint model and a case file for it into `dir`. */
std::filesystem::path writeCase(const test::TempDir& dir, const nlohmann::json& extra = {}) {
    test::twoJointModel().save(dir.path(), "twojoint");
    nlohmann::json c = {{"model", "twojoint.gltf"}, {"times", {0.25, 0.75}}, {"size", {64, 64}}};
    for (const auto& [k, v] : extra.items())
        c[k] = v;
    std::ofstream(dir / "case.json") << c.dump(2);
    return dir / "case.json";
}

TEST(CaptureTool, CaseMatchesItsGoldensAndReportsAMismatch) {
    test::TempDir dir;
    const auto casePath = writeCase(dir);
    std::string out;
    int status = capture("--case " + casePath.string() + " --update", &out);
    SKIP_WITHOUT_GL(out);
    ASSERT_EQ(status, 0) << out;
    ASSERT_TRUE(std::filesystem::exists(dir / "case.t0.250.png"));
    ASSERT_EQ(capture("--case " + casePath.string(), &out), 0) << out;
    EXPECT_NE(out.find("case t=0.750: match"), std::string::npos) << out;

    // Paint a block of the golden: 100 of 4096 pixels differ, far over 0.1%.
    auto golden = capture::readPng(dir / "case.t0.750.png");
    ASSERT_TRUE(golden.ok());
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x)
            golden->rgba[(std::size_t(y) * 64 + std::size_t(x)) * 4] ^= 0x80;
    ASSERT_TRUE(capture::writePng(dir / "case.t0.750.png", *golden).ok());
    EXPECT_EQ(capture("--case " + casePath.string() + " --out " + (dir / "result").string(), &out),
              1);
    EXPECT_NE(out.find("case t=0.750: MISMATCH"), std::string::npos) << out;
    EXPECT_TRUE(std::filesystem::exists(dir / "result" / "case.t0.750.actual.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "result" / "case.t0.750.diff.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "result" / "case.report.txt"));
    EXPECT_FALSE(std::filesystem::exists(dir / "result" / "case.t0.250.actual.png"));
}

TEST(CaptureTool, CaseWithMissingModelSkipsOnlyWhenAllowed) {
    test::TempDir dir;
    std::ofstream(dir / "absent.json")
        << R"({"model": "nowhere.glb", "times": [0], "skip_if_missing": true})";
    std::string out;
    EXPECT_EQ(capture("--case " + (dir / "absent.json").string(), &out), 77);
    std::ofstream(dir / "required.json") << R"({"model": "nowhere.glb", "times": [0]})";
    EXPECT_EQ(capture("--case " + (dir / "required.json").string(), &out), 1);
    std::ofstream(dir / "bad.json") << R"({"model": "x.glb"})";
    EXPECT_EQ(capture("--case " + (dir / "bad.json").string(), &out), 2);
    EXPECT_NE(out.find("\"times\""), std::string::npos) << out;
}

TEST(CaptureTool, PluginAddsAPassAndTakesParameters) {
    test::TempDir dir;
    const auto model = test::twoJointModel().save(dir.path(), "twojoint");
    const std::string base = model.string() + " --time 0.5 --size 48x48 --json ";
    std::string out;
    int status = capture(base + "--out " + (dir / "plain").string() + " 2>/dev/null", &out);
    SKIP_WITHOUT_GL(out);
    ASSERT_EQ(status, 0) << out;
    ASSERT_EQ(capture(base + "--out " + (dir / "tinted").string() + " --plugin " + kLib +
                          "/libtint_plugin.so --set red=3 2>/dev/null",
                      &out),
              0)
        << out;
    bool hasTintPass = false;
    const auto report = nlohmann::json::parse(out);
    for (const auto& p : report["frames"][0]["passes"])
        hasTintPass = hasTintPass || p["name"] == "tint";
    EXPECT_TRUE(hasTintPass) << out;
    auto plain = capture::readPng(dir / "plain" / "twojoint_bend_t0.500.png");
    auto tinted = capture::readPng(dir / "tinted" / "twojoint_bend_t0.500.png");
    ASSERT_TRUE(plain.ok() && tinted.ok());
    long redGain = 0;
    for (std::size_t i = 0; i < plain->rgba.size(); i += 4)
        redGain += long(tinted->rgba[i]) - long(plain->rgba[i]);
    EXPECT_GT(redGain, 48L * 48L * 10L) << "the tint pass must raise red everywhere";

    EXPECT_EQ(capture(base + "--out " + (dir / "x").string() + " --plugin " + kLib +
                          "/libtint_plugin.so --set green=2",
                      &out),
              1);
    EXPECT_NE(out.find("unknown parameter 'green'"), std::string::npos) << out;
}

TEST(CaptureTool, PluginInterfaceVersionIsChecked) {
    test::TempDir dir;
    const auto model = test::twoJointModel().save(dir.path(), "twojoint");
    std::string out;
    EXPECT_EQ(capture(model.string() + " --out " + (dir / "x").string() + " --plugin " + kLib +
                          "/libtint_plugin_wrong.so",
                      &out),
              1);
    EXPECT_NE(
        out.find("built for plugin interface 'glass.plugin/0', this engine needs 'glass.plugin/9'"),
        std::string::npos)
        << out;
    EXPECT_EQ(
        capture(model.string() + " --out " + (dir / "x").string() + " --plugin /nonexistent.so",
                &out),
        1);
    EXPECT_NE(out.find("/nonexistent.so: cannot load"), std::string::npos) << out;
}

TEST(CaptureTool, EnvironmentComesFromTheHdrFile) {
    test::TempDir dir;
    const auto model = test::twoJointModel().save(dir.path(), "twojoint");
    test::writeHdr(dir / "red.hdr", 64, 32, 2.0f, 0.05f, 0.05f);
    std::string out;
    const int status = capture(model.string() + " --size 32x32 --env " +
                                   (dir / "red.hdr").string() + " --out " + (dir / "red").string(),
                               &out);
    SKIP_WITHOUT_GL(out);
    ASSERT_EQ(status, 0) << out;
    auto image = capture::readPng(dir / "red" / "twojoint_bend_t0.000.png");
    ASSERT_TRUE(image.ok());
    // The corner pixel is background: red sky.
    EXPECT_GT(int(image->rgba[0]), 200);
    EXPECT_LT(int(image->rgba[1]), 100);

    std::ofstream(dir / "bad.hdr") << "#?RADIANCE\nnot really an image";
    EXPECT_EQ(capture(model.string() + " --env " + (dir / "bad.hdr").string() + " --out " +
                          (dir / "bad").string(),
                      &out),
              1);
    EXPECT_NE(out.find("asset::loadHdr(): bad.hdr: not a decodable image"), std::string::npos)
        << out;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
}

TEST(CaptureTool, RefractionPluginLoads) {
    // The module, loaded with glass on while the built-in plugin is off, draws the sphere as
    // the built-in plugin does: the same image, and not the opaque one.
    test::TempDir dir;
    const std::string sphere = "builtin:sphere --size 32x32 --glass all ";
    std::string out;
    const int status =
        capture(sphere + "--method opaque --out " + (dir / "module").string() + " --plugin " +
                    kLib + "/libglass_refraction.so --set method=dir --set glass=all",
                &out);
    SKIP_WITHOUT_GL(out);
    ASSERT_EQ(status, 0) << out;
    ASSERT_EQ(capture(sphere + "--method dir --out " + (dir / "builtin").string(), &out), 0) << out;
    ASSERT_EQ(capture(sphere + "--method opaque --out " + (dir / "opaque").string(), &out), 0)
        << out;
    auto frame = [&](const char* run) {
        auto image = capture::readPng(dir / run / "builtin_sphere_rest_t0.000.png");
        EXPECT_TRUE(image.ok()) << run << ": " << (image.ok() ? "" : image.error().message);
        return image ? image->rgba : std::vector<std::uint8_t>{};
    };
    const auto module = frame("module"), builtin = frame("builtin"), opaque = frame("opaque");
    ASSERT_EQ(module.size(), opaque.size());
    std::size_t glass = 0;
    for (std::size_t i = 0; i < module.size(); ++i)
        glass += std::abs(int(module[i]) - int(opaque[i])) > 8;
    EXPECT_GT(glass, 100u) << "the module drew no glass";
    EXPECT_EQ(module, builtin);
}

} // namespace

namespace {

TEST(CaptureTool, ExistingOutputIsKeptWithoutForceAndAFailedRunLeavesNothing) {
    test::TempDir dir;
    std::string out;
    const std::string args = "builtin:sphere?segments=16 --size 32x32 --frames 0:0.5:0.5 --out " +
                             (dir / "frames").string();
    const int first = capture(args, &out);
    SKIP_WITHOUT_GL(out);
    ASSERT_EQ(first, 0) << out;
    const auto frame = dir / "frames" / "builtin_sphere_segments_16_rest_t0.500.png";
    ASSERT_TRUE(std::filesystem::exists(frame)) << out;
    const auto before = std::filesystem::last_write_time(frame);
    // A second run refuses before writing anything...
    EXPECT_EQ(capture(args + " --contact-sheet " + (dir / "sheet.png").string(), &out), 1);
    EXPECT_NE(out.find("exists (use --force to replace it); nothing written"), std::string::npos)
        << out;
    EXPECT_FALSE(std::filesystem::exists(dir / "sheet.png"));
    EXPECT_EQ(std::filesystem::last_write_time(frame), before);
    // ... and --force replaces.
    EXPECT_EQ(capture(args + " --force --contact-sheet " + (dir / "sheet.png").string(), &out), 0)
        << out;
    EXPECT_TRUE(std::filesystem::exists(dir / "sheet.png"));

    // A run that fails on its second frame (the contact sheet's folder is a file, so writing it
    // fails last) removes the frames it wrote.
    std::ofstream(dir / "blocker") << "a file, not a folder";
    EXPECT_EQ(capture("builtin:sphere?segments=16 --size 32x32 --frames 0:0.5:0.5 --out " +
                          (dir / "second").string() + " --contact-sheet " +
                          (dir / "blocker" / "sheet.png").string(),
                      &out),
              1)
        << out;
    std::size_t left = 0;
    if (std::filesystem::exists(dir / "second"))
        for ([[maybe_unused]] const auto& entry :
             std::filesystem::directory_iterator(dir / "second"))
            ++left;
    EXPECT_EQ(left, 0u) << "files left by a failed run";
}

} // namespace
