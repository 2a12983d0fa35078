// The viewer's presets, --set assignments and orbit camera, without a window.
#include "Preset.h"
#include "OrbitCamera.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <fstream>

namespace {

plugin::ParameterSet glassParameters() {
    plugin::ParameterSet p;
    p.declare({"method",
               "Method",
               plugin::Parameter::Type::Enum,
               0,
               0,
               3,
               {"opaque", "sir", "isr", "dir"},
               ""});
    p.declare({"ior", "IOR", plugin::Parameter::Type::Float, 0.0, 4.0, 0.0, {}, ""});
    p.declare({"tint", "Tint", plugin::Parameter::Type::Color, 0.0, 1.0, 1.0, {}, ""});
    return p;
}

struct Scopes {
    plugin::ParameterSet viewer =
        viewer::viewerParameters({"walk", "wave"}, {"sky", "studio"}, {"opaque", "sir", "dir"});
    plugin::ParameterSet glass = glassParameters();
    std::vector<viewer::Scope> list() { return {{"viewer", &viewer}, {"refraction", &glass}}; }
};

TEST(ViewerPreset, RoundTripsEveryParameterAndTheCamera) {
    Scopes a;
    ASSERT_TRUE(a.glass.set("ior", "1.333").ok());
    ASSERT_TRUE(a.glass.set("method", "isr").ok());
    ASSERT_TRUE(a.glass.set("tint", "0.25,0.5,1").ok());
    ASSERT_TRUE(a.viewer.set("clip", "wave").ok());
    ASSERT_TRUE(a.viewer.set("exposure", "1.75").ok());
    ASSERT_TRUE(a.viewer.set("split", "on").ok());
    viewer::Orbit orbit{{1.0f, 2.0f, 3.0f}, 4.5f, 0.25f, -0.5f};
    test::TempDir dir;
    ASSERT_TRUE(viewer::writePreset(dir / "p.json", viewer::presetJson(a.list(), orbit)).ok());

    Scopes b;
    viewer::Orbit restored;
    auto preset = viewer::readPreset(dir / "p.json");
    ASSERT_TRUE(preset.ok()) << preset.error().message;
    auto applied = viewer::applyPreset(*preset, b.list(), restored, "p.json");
    ASSERT_TRUE(applied.ok()) << applied.error().message;
    for (auto [from, to] : {std::pair{&a.viewer, &b.viewer}, std::pair{&a.glass, &b.glass}})
        for (const auto& p : from->declarations())
            EXPECT_EQ(to->text(p.name), from->text(p.name)) << p.name;
    EXPECT_EQ(restored.target, orbit.target);
    EXPECT_FLOAT_EQ(restored.distance, 4.5f);
    EXPECT_FLOAT_EQ(restored.elevation, -0.5f);
}

TEST(ViewerPreset, ABadPresetChangesNothingAndNamesTheKey) {
    Scopes s;
    viewer::Orbit orbit;
    const nlohmann::json bad = {
        {"format", viewer::kPresetFormat},
        {"parameters", {{"refraction", {{"ior", "1.5"}, {"method", "magic"}}}}}};
    auto applied = viewer::applyPreset(bad, s.list(), orbit, "bad.json");
    ASSERT_FALSE(applied.ok());
    EXPECT_NE(applied.error().message.find("bad.json: parameters.refraction.method"),
              std::string::npos)
        << applied.error().message;
    EXPECT_EQ(s.glass.text("ior"), "0") << "the valid ior before the bad key was not applied";

    for (const nlohmann::json& preset :
         {nlohmann::json{{"parameters", nlohmann::json::object()}},
          nlohmann::json{{"format", viewer::kPresetFormat}, {"colour", 1}},
          nlohmann::json{{"format", viewer::kPresetFormat},
                         {"parameters", {{"nosuchplugin", nlohmann::json::object()}}}},
          nlohmann::json{{"format", viewer::kPresetFormat},
                         {"parameters", {{"viewer", {{"exposure", 2}}}}}},
          nlohmann::json{{"format", viewer::kPresetFormat}, {"camera", {{"distance", -1}}}},
          nlohmann::json{{"format", viewer::kPresetFormat}, {"camera", {{"target", {1, 2}}}}}})
        EXPECT_FALSE(viewer::applyPreset(preset, s.list(), orbit, "p.json").ok()) << preset;

    test::TempDir dir;
    std::ofstream(dir / "broken.json") << "{ not json";
    auto read = viewer::readPreset(dir / "broken.json");
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.error().message.find("broken.json"), std::string::npos);
}

TEST(ViewerPreset, SetAssignmentsFindTheirScope) {
    Scopes s;
    EXPECT_TRUE(viewer::setAssignment(s.list(), "ior=2.417").ok());
    EXPECT_EQ(s.glass.text("ior"), "2.417");
    EXPECT_TRUE(viewer::setAssignment(s.list(), "viewer.exposure=2").ok());
    EXPECT_EQ(s.viewer.text("exposure"), "2");
    EXPECT_TRUE(viewer::setAssignment(s.list(), "refraction.method=sir").ok());
    EXPECT_EQ(s.glass.text("method"), "sir");
    for (const char* bad : {"ior", "=1", "nosuch=1", "other.ior=1", "ior=9", "method=magic"})
        EXPECT_FALSE(viewer::setAssignment(s.list(), bad).ok()) << bad;
}

TEST(ViewerPreset, CopyValuesKeepsWhatTheNewSetAccepts) {
    Scopes s;
    ASSERT_TRUE(s.viewer.set("clip", "wave").ok());
    ASSERT_TRUE(s.viewer.set("speed", "2").ok());
    plugin::ParameterSet other = viewer::viewerParameters({"run"}, {"sky"}, {"dir"});
    viewer::copyValues(s.viewer, other);
    EXPECT_EQ(other.text("speed"), "2");
    EXPECT_EQ(other.text("clip"), "run") << "a clip the new model lacks falls back to its first";
}

TEST(OrbitCamera, FramesOrbitsPansAndZooms) {
    render::Bounds bounds;
    bounds.add({-1.0f, 0.0f, -1.0f});
    bounds.add({1.0f, 2.0f, 1.0f});
    viewer::OrbitCamera camera;
    camera.frame(bounds, 1.0f);
    const render::Camera framed = render::frameBounds(bounds, 1.0f, camera.yfov());
    EXPECT_NEAR(glm::distance(camera.camera(1.0f).position, framed.position), 0.0f, 1e-4f);

    camera.orbit({0.0f, 1e6f}, 100.0f);
    EXPECT_LT(camera.orbitState().elevation, 1.56f) << "elevation stays below the pole";
    camera.reset();
    camera.orbit({50.0f, 0.0f}, 100.0f); // half the height: a quarter turn
    EXPECT_NEAR(camera.orbitState().azimuth, -glm::half_pi<float>(), 1e-5f);

    camera.reset();
    const glm::vec3 before = camera.orbitState().target;
    camera.pan({10.0f, 0.0f}, 100.0f);
    const render::Camera moved = camera.camera(1.0f);
    // The target moved along the view's horizontal axis, not towards the camera.
    const glm::vec3 shift = camera.orbitState().target - before;
    EXPECT_GT(glm::length(shift), 0.0f);
    EXPECT_NEAR(glm::dot(shift, glm::vec3(glm::inverse(moved.view)[2])), 0.0f, 1e-5f);

    const float distance = camera.orbitState().distance;
    camera.zoom(1.0f);
    EXPECT_NEAR(camera.orbitState().distance, 0.9f * distance, 1e-5f);
    camera.zoom(-1000.0f);
    EXPECT_LE(camera.orbitState().distance, 50.0f * bounds.radius() + 1e-3f);
}

} // namespace
