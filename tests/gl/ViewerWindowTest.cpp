// glass-viewer in a real window: an X server from xvfb-run, GLX on Mesa, real input events from
// xdotool (tests/viewer/drive_viewer.sh). Skipped where xvfb-run or xdotool is missing
// (scripts/deps installs both).
#include "support/TestSupport.h"

#include "engine/asset/SceneFile.h"
#include "engine/capture/Image.h"
#include "engine/capture/Metrics.h"
#include "engine/render/WorldLoader.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <regex>
#include <set>
#include <string>

namespace {

const std::string kViewer = std::string(GLASS_BIN_DIR) + "/glass-viewer";
const std::string kCapture = std::string(GLASS_BIN_DIR) + "/glass-capture";
const std::string kDrive = std::string(GLASS_SOURCE_DIR) + "/tests/viewer/drive_viewer.sh";
const std::string kDrivePanel = std::string(GLASS_SOURCE_DIR) + "/tests/viewer/drive_panel.sh";
// A window small enough for a fast test; the panel takes 45% of it, up to 380 pixels.
const std::string kWindow = "--size 640x400";
const int kViewWidth = 640 - 640 * 45 / 100;

class ViewerWindow : public ::testing::Test {
protected:
    void SetUp() override {
        if (test::runCommand("command -v xvfb-run >/dev/null && command -v xdotool >/dev/null") !=
            0)
            GTEST_SKIP() << "xvfb-run and xdotool are needed (scripts/deps installs them)";
    }
    /** Runs `command` in a fresh X server (1024x768) with a private config folder. */
    int inX(const std::string& command, std::string* output) {
        // The X authority in the test's own folder: xvfb-run then makes no temporary folder of
        // its own, whose removal failed now and then with tests running side by side (exit 5,
        // "problem while cleaning up temporary directory", whatever the viewer returned).
        return test::runCommand("XDG_CONFIG_HOME='" + mConfig.path().string() +
                                    "' xvfb-run -a -f '" + (mConfig / "Xauthority").string() +
                                    "' -s '-screen 0 1024x768x24' " + command,
                                output);
    }
    /** An interactive run (no --frames) in a fresh X server: the viewer started with
     *  `arguments` and the test window size, its window ($w) focused, the shell commands of
     *  `input` run (xdotool), then Escape, which quits and saves the session and scene. */
    int interactively(const std::string& arguments, const std::string& input, std::string* output) {
        return inX("sh -c '" + kViewer + " " + arguments + " " + kWindow +
                       " & pid=$!;"
                       " w=$(timeout 60 xdotool search --sync --onlyvisible --name ^glass-viewer$"
                       " | head -n 1);"
                       " for i in $(seq 50); do xdotool mousemove --window $w 40 40 &&"
                       " xdotool windowfocus --sync $w && break; sleep 0.1; done; " +
                       input + " xdotool key Escape; wait $pid'",
                   output);
    }
    void expectViewerMatchesCapture(const std::string& viewerArguments,
                                    const std::string& captureArguments);
    /** The viewer started with `arguments`, driven through its panel by `steps`
     *  (tests/viewer/drive_panel.sh), then quit with Escape. */
    int throughThePanel(const std::string& steps, const std::string& arguments,
                        std::string* output) {
        const auto file = mOut / "steps.txt";
        std::ofstream(file) << steps;
        return inX(kDrivePanel + " " + kViewer + " " + mOut.path().string() + " " + file.string() +
                       " " + arguments,
                   output);
    }
    test::TempDir mConfig, mOut;
};

capture::Image load(const std::filesystem::path& path) {
    auto image = capture::readPng(path);
    EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.error().message);
    return image.ok() ? *image : capture::Image{};
}

/** The viewer's offscreen screenshot of the default character after three frames of 1/30 s
 *  (the walk at t = 0.1 s) against glass-capture's frame; `viewerArguments` and
 *  `captureArguments` add the same setting to each. */
void ViewerWindow::expectViewerMatchesCapture(const std::string& viewerArguments,
                                              const std::string& captureArguments) {
    const std::filesystem::path outDir = mOut.path();
    std::string out;
    const auto shot = outDir / "viewer.png";
    ASSERT_EQ(inX(kViewer + " " + kWindow + " --no-restore --frames 3 --screenshot " +
                      shot.string() + " --screenshot-size 176x200 --exit " + viewerArguments,
                  &out),
              0)
        << out;
    // The view's aspect (352x400), so that both frame the character alike.
    const std::string assets = std::string(GLASS_SOURCE_DIR) + "/assets";
    ASSERT_EQ(test::runCommand(kCapture + " " + assets + "/models/glass_figure.glb --env " +
                                   assets +
                                   "/env/sunset_sky.hdr --time 0.1 --size 176x200 --ground --out " +
                                   (outDir / "capture").string() + " --force " + captureArguments,
                               &out),
              0)
        << out;
    const capture::Image viewer = load(shot);
    const capture::Image reference = load(outDir / "capture" / "glass_figure_walk_t0.100.png");
    const capture::Comparison c = capture::compare(viewer, reference, {2, 0.0});
    EXPECT_TRUE(c.passed) << c.failingPixels << " pixels differ, max " << c.maxAbsDiff;
}

double luminance(const capture::Image& image, int x, int y) {
    const std::uint8_t* p =
        &image.rgba[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 4];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/** Pixels of the rectangle [x0, x1) x [0, height) that differ by more than 8 in any channel. */
std::size_t differingPixels(const capture::Image& a, const capture::Image& b, int x0, int x1) {
    std::size_t count = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c) {
                const std::size_t i =
                    (std::size_t(y) * std::size_t(a.width) + std::size_t(x)) * 4 + std::size_t(c);
                if (std::abs(int(a.rgba[i]) - int(b.rgba[i])) > 8) {
                    ++count;
                    break;
                }
            }
    return count;
}

TEST_F(ViewerWindow, ScriptedRunDrawsTheCharacterAndThePanel) {
    std::string out;
    const auto shot = mOut / "window.png";
    // No model: the project's default character.
    ASSERT_EQ(inX(kViewer + " " + kWindow + " --no-restore --frames 3 --screenshot " +
                      shot.string() + " --screenshot-panel --exit",
                  &out),
              0)
        << out;
    EXPECT_NE(out.find("3 frames, median frame"), std::string::npos) << out;
    const capture::Image image = load(shot);
    ASSERT_EQ(image.width, 640);
    ASSERT_EQ(image.height, 400);
    // The panel: a dark window with light text.
    double panelSum = 0.0;
    std::size_t text = 0, panelPixels = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = kViewWidth + 4; x < image.width - 4; ++x, ++panelPixels) {
            const double l = luminance(image, x, y);
            panelSum += l;
            text += l > 180.0;
        }
    EXPECT_LT(panelSum / double(panelPixels), 60.0);
    EXPECT_GT(text, 500u) << "no text in the panel";
    // The view is not blank: the character and the environment give many distinct values.
    std::set<int> values;
    for (int y = 0; y < image.height; y += 4)
        for (int x = 0; x < kViewWidth; x += 4)
            values.insert(int(luminance(image, x, y)));
    EXPECT_GT(values.size(), 64u);
}

TEST_F(ViewerWindow, OffscreenScreenshotOfTheDefaultCharacterMatchesGlassCapture) {
    expectViewerMatchesCapture("", "");
}

TEST_F(ViewerWindow, SubdivisionSliderRefinesLikeGlassCapture) {
    expectViewerMatchesCapture("--set subdiv=1", "--subdiv 1");
}

TEST_F(ViewerWindow, RealInputEventsChangeTheImageAndEscapeQuits) {
    std::string out;
    const int status = inX(kDrive + " " + kViewer + " " + mOut.path().string() +
                               " builtin:sphere " + kWindow + " --no-restore --set method=opaque",
                           &out);
    ASSERT_EQ(status, 0) << out;
    EXPECT_NE(out.find(", 0 GL errors"), std::string::npos) << out;
    const capture::Image first = load(mOut / "glass-viewer-0001.png");
    const capture::Image again = load(mOut / "glass-viewer-0002.png");
    const capture::Image method = load(mOut / "glass-viewer-0003.png");
    const capture::Image orbited = load(mOut / "glass-viewer-0004.png");
    ASSERT_EQ(first.width, kViewWidth);
    const std::size_t area = std::size_t(first.width) * std::size_t(first.height);
    EXPECT_EQ(differingPixels(first, again, 0, first.width), 0u) << "no input, same image";
    EXPECT_GT(differingPixels(again, method, 0, first.width), area / 100)
        << "the M key switches opaque -> sir";
    EXPECT_GT(differingPixels(method, orbited, 0, first.width), area / 100)
        << "a drag orbits the camera";
}

TEST_F(ViewerWindow, QuittingSavesTheSessionAndTheNextStartRestoresIt) {
    std::string out;
    // An interactive run, ended with the Escape key, saves its settings.
    ASSERT_EQ(interactively("builtin:sphere --set method=sir --set ior=1.77", "", &out), 0) << out;
    const auto session = mConfig / "glass-viewer" / "last-session.json";
    ASSERT_TRUE(std::filesystem::exists(session)) << out;
    // The next run starts from it...
    const auto restored = mOut / "restored.png", explicitly = mOut / "explicit.png",
               fresh = mOut / "fresh.png";
    const std::string scripted = " builtin:sphere " + kWindow + " --frames 1 --exit --screenshot ";
    ASSERT_EQ(inX(kViewer + scripted + restored.string(), &out), 0) << out;
    ASSERT_EQ(inX(kViewer + scripted + explicitly.string() +
                      " --no-restore --set method=sir --set ior=1.77",
                  &out),
              0)
        << out;
    ASSERT_EQ(inX(kViewer + scripted + fresh.string() + " --no-restore", &out), 0) << out;
    const capture::Image a = load(restored), b = load(explicitly), c = load(fresh);
    EXPECT_EQ(differingPixels(a, b, 0, a.width), 0u);
    EXPECT_GT(differingPixels(a, c, 0, a.width), 100u) << "sir at 1.77 differs from the default";
}

TEST_F(ViewerWindow, AddedModelJoinsTheSceneAndTheNextStartRestoresIt) {
    std::string out;
    // A second model added by path (--add: the panel's Add button), then Escape: the scene is
    // saved with the session.
    ASSERT_EQ(interactively("builtin:sphere --add \"builtin:sphere?segments=24\"", "", &out), 0)
        << out;
    const auto saved = mConfig / "glass-viewer" / "last-scene.json";
    auto world = asset::loadScene(saved);
    ASSERT_TRUE(world.ok()) << (world.ok() ? "" : world.error().message) << out;
    ASSERT_EQ(world->characters.size(), 2u);
    EXPECT_EQ(world->characters[0].modelPath, "builtin:sphere");
    EXPECT_EQ(world->characters[1].modelPath, "builtin:sphere?segments=24");
    EXPECT_GT(world->characters[1].placement.translation.x,
              world->characters[0].placement.translation.x + 1.0)
        << "added right of the first, not on top of it";
    // A start without a model restores that scene and draws it.
    const auto shot = mOut / "restored.png";
    ASSERT_EQ(
        inX(kViewer + " " + kWindow + " --frames 1 --exit --screenshot " + shot.string(), &out), 0)
        << out;
    EXPECT_NE(out.find("restored the last scene (2 characters)"), std::string::npos) << out;
    EXPECT_TRUE(std::filesystem::exists(shot));
}

TEST_F(ViewerWindow, AClickSelectsACharacterAndCtrlDragMovesItOverTheGround) {
    std::string out;
    // Two spheres side by side in the 352-pixel-wide view, the first selected at start; a click
    // on the right one selects it, Ctrl + a drag to the right moves it, Escape saves the scene.
    // The click is held for a second, and the drag's steps are a few frames apart: Dear ImGui
    // 1.86's GLFW backend can miss the release of a press and release that fall in one frame,
    // and the viewer ignores the pointer's motion in the frame of the press (slow frames:
    // sanitizer builds, a loaded machine).
    ASSERT_EQ(interactively("builtin:sphere \"builtin:sphere?segments=24\" --no-restore",
                            "sleep 0.5; xdotool mousemove --window $w 260 200 mousedown 1; sleep 1;"
                            " xdotool mouseup 1; sleep 1;"
                            " xdotool keydown ctrl mousedown 1; sleep 0.6;"
                            " for x in 270 280 290 300 310; do sleep 0.3;"
                            " xdotool mousemove --window $w $x 200; done;"
                            " sleep 0.8; xdotool mouseup 1 keyup ctrl; sleep 0.3;",
                            &out),
              0)
        << out;
    auto world = asset::loadScene(mConfig / "glass-viewer" / "last-scene.json");
    ASSERT_TRUE(world.ok()) << (world.ok() ? "" : world.error().message) << out;
    ASSERT_EQ(world->characters.size(), 2u);
    const auto before =
        render::loadWorld(std::vector<std::string>{"builtin:sphere", "builtin:sphere?segments=24"});
    ASSERT_TRUE(before.ok());
    EXPECT_EQ(world->characters[0].placement.translation,
              before->characters[0].placement.translation)
        << "the first is no longer selected";
    const glm::dvec3 moved =
        world->characters[1].placement.translation - before->characters[1].placement.translation;
    EXPECT_GT(moved.x, 0.1) << "the picked one dragged to the right";
    EXPECT_EQ(moved.y, 0.0) << "over the ground, not up";
}

/** glass-capture's frame of `what` (a scene or model file, and options) at `time`, `size`
 *  pixels, written into `out`. */
capture::Image captureFrame(const std::string& what, const std::string& time, glm::ivec2 size,
                            const std::filesystem::path& out) {
    std::string log;
    EXPECT_EQ(test::runCommand(kCapture + " " + what + " --time " + time + " --size " +
                                   std::to_string(size.x) + "x" + std::to_string(size.y) +
                                   " --out " + out.string() + " --force",
                               &log),
              0)
        << log;
    if (std::filesystem::is_directory(out))
        for (const auto& entry : std::filesystem::directory_iterator(out))
            if (entry.path().extension() == ".png")
                return load(entry.path());
    ADD_FAILURE() << "no frame in " << out << ": " << log;
    return {};
}

TEST_F(ViewerWindow, AMorphWeightAndACrossfadeSetInThePanelAreSavedAndCapturedAsShown) {
    // Through the panel with real input, each widget found by name (--ui-map): "Crossfade (s)"
    // set to 0.6, the morph target "breathe" ticked and set to 0.8, C for the next clip (a
    // crossfade from now), six frame steps, F12, then Escape, which saves the scene.
    // glass-capture of the saved scene at the screenshot's scene time draws the screenshot;
    // the same scene without the morph weight, or without the crossfade, does not.
    const std::string model = std::string(GLASS_SOURCE_DIR) + "/assets/models/glass_figure.glb";
    std::string out;
    ASSERT_EQ(throughThePanel("enter Crossfade (s)=0.6\n"
                              "click Morph weights\n"
                              "click set glass_figure: breathe\n"
                              "enter glass_figure: breathe=0.8\n"
                              "key c\n"
                              "key Right\nkey Right\nkey Right\nkey Right\nkey Right\nkey Right\n"
                              "screenshot 1\n",
                              model + " --size 640x700 --no-restore --set playing=0"
                                      " --set render-scale=1 --set temporal=0",
                              &out),
              0)
        << out;
    std::smatch at;
    ASSERT_TRUE(std::regex_search(out, at, std::regex("at scene time ([0-9.]+) s"))) << out;
    const auto saved = mConfig / "glass-viewer" / "last-scene.json";
    auto world = asset::loadScene(saved);
    ASSERT_TRUE(world.ok()) << (world.ok() ? "" : world.error().message) << out;
    const scene::Performance& p = world->characters.at(0).performance;
    ASSERT_EQ(p.morphs.size(), 1u);
    EXPECT_NEAR(p.morphs[0].value, 0.8, 1e-6);
    ASSERT_EQ(p.transitions.size(), 1u);
    EXPECT_NEAR(p.transitions[0].duration, 0.6, 1e-6);
    EXPECT_EQ(p.transitions[0].to, 1) << "C: from the first clip to the second";
    EXPECT_TRUE(world->camera.has_value()) << "the view's camera is saved";

    const capture::Image shot = load(mOut / "glass-viewer-0001.png");
    const glm::ivec2 size(shot.width, shot.height);
    const double same =
        capture::score(captureFrame(saved.string(), at[1], size, mOut / "saved"), shot).psnr;
    std::printf("the saved scene's capture against the viewer's screenshot: %.2f dB\n", same);
    EXPECT_GE(same, 50.0); // measured 58.1 dB
    std::ifstream in(saved);
    const nlohmann::json scene = nlohmann::json::parse(in);
    for (const char* key : {"morph_weights", "transitions"}) {
        nlohmann::json without = scene;
        without["characters"][0].erase(key);
        const auto path = mOut / (std::string("without_") + key + ".json");
        std::ofstream(path) << without.dump();
        const double other =
            capture::score(captureFrame(path.string(), at[1], size, mOut / key), shot).psnr;
        std::printf("without %s: %.2f dB\n", key, other);
        EXPECT_LT(other, same - 6.0) << "the panel's " << key << " show in the screenshot";
    }
}

TEST_F(ViewerWindow, TheFilesCamerasAreListedAndLookedThrough) {
    // A model with a camera whose yfov its clip plays (0.6 -> 1 rad over a second): chosen in
    // the panel's list (the scene section closed to bring it into the window), the view looks
    // through it as glass-capture does (a model's capture looks through its first camera), at
    // the screenshot's time; the scene Escape saves looks through it too.
    const auto model = test::pointerTwoJointModel().save(mOut.path(), "eye");
    std::string out;
    ASSERT_EQ(throughThePanel("key Right\nkey Right\nkey Right\nkey Right\nkey Right\n"
                              "click Scene\nclick eye.gltf: eye\nscreenshot 1\n",
                              model.string() +
                                  " --size 640x400 --no-restore --set playing=0"
                                  " --set render-scale=1 --set temporal=0 --set method=opaque",
                              &out),
              0)
        << out;
    std::smatch at;
    ASSERT_TRUE(std::regex_search(out, at, std::regex("at scene time ([0-9.]+) s"))) << out;
    const capture::Image shot = load(mOut / "glass-viewer-0001.png");
    const capture::Image captured =
        captureFrame(model.string() + " --ground --method opaque --env " +
                         std::string(GLASS_SOURCE_DIR) + "/assets/env/sunset_sky.hdr",
                     at[1], {shot.width, shot.height}, mOut / "capture");
    const double psnr = capture::score(captured, shot).psnr;
    std::printf("through the file's camera against glass-capture: %.2f dB\n", psnr);
    EXPECT_GE(psnr, 50.0);
    // Escape saved the scene looking through that camera: its capture follows the camera too.
    const auto saved = mConfig / "glass-viewer" / "last-scene.json";
    auto world = asset::loadScene(saved);
    ASSERT_TRUE(world.ok()) << (world.ok() ? "" : world.error().message) << out;
    ASSERT_TRUE(world->camera && world->camera->through);
    EXPECT_EQ(world->characters[0].model->nodes[std::size_t(world->camera->through->node)].name,
              "eye");
    const double savedPsnr = capture::score(captureFrame(saved.string() + " --method opaque", at[1],
                                                         {shot.width, shot.height}, mOut / "saved"),
                                            shot)
                                 .psnr;
    std::printf("the saved scene's capture against the screenshot: %.2f dB\n", savedPsnr);
    EXPECT_GE(savedPsnr, 50.0);
}

TEST_F(ViewerWindow, BadInputFailsClearlyWithoutOutput) {
    std::string out;
    const auto shot = mOut / "never.png";
    struct Case {
        std::string arguments, message;
    };
    std::ofstream(mOut / "bad-preset.json") << R"({"format": "glass-viewer-preset/1", "x": 1})";
    for (const Case& c :
         {Case{(mOut / "missing.glb").string(), "missing.glb"},
          Case{"builtin:sphere --preset " + (mOut / "bad-preset.json").string(),
               "bad-preset.json: unknown key 'x'"},
          Case{"builtin:sphere --set nosuch=1", "--set nosuch: no such parameter"},
          Case{"builtin:sphere --plugin " + (mOut / "nothing.so").string(), "nothing.so"}}) {
        EXPECT_EQ(inX(kViewer + " " + c.arguments + " " + kWindow +
                          " --no-restore --frames 1 --exit --screenshot " + shot.string(),
                      &out),
                  1)
            << c.arguments << "\n"
            << out;
        EXPECT_NE(out.find(c.message), std::string::npos) << out;
        EXPECT_FALSE(std::filesystem::exists(shot));
    }
    EXPECT_EQ(test::runCommand(kViewer + " --frames 0", &out), 2);
    EXPECT_EQ(test::runCommand(kViewer + " --screenshot x.png", &out), 2);
}

} // namespace
