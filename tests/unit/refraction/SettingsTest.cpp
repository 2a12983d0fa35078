// The refraction plugin's parameters: decoded into Settings (what the passes and the reference
// read), and its material presets, plain parameter data with no GL and no UI library.
#include "Settings.h"
#include "refraction/RefractionPlugin.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>

namespace {

TEST(MaterialPresets, SetIorAndDispersionFromTheAbbeNumber) {
    auto glass = refraction::createPlugin();
    plugin::ParameterSet& p = glass->parameters();
    ASSERT_GE(p.presets().size(), 11u);
    ASSERT_TRUE(p.applyPreset("diamond  2.417").ok());
    EXPECT_DOUBLE_EQ(p.number("ior"), 2.417);
    EXPECT_NEAR(p.number("dispersion"), 20.0 / 55.3, 1e-4);
    ASSERT_TRUE(p.applyPreset("the material's own").ok());
    EXPECT_EQ(p.number("ior"), 0.0);
    EXPECT_EQ(p.number("dispersion"), -1.0);
    for (const plugin::ParameterPreset& preset : p.presets()) {
        ASSERT_TRUE(p.applyPreset(preset.name).ok()) << preset.name;
        EXPECT_TRUE(p.number("ior") == 0.0 || (p.number("ior") > 1.3 && p.number("ior") < 2.5))
            << preset.name;
    }
}

TEST(Settings, DecodesEveryChoice) {
    // Every parameter set to a value other than its default, decoded into its field: a table
    // that must name every parameter of the plugin (a new one fails until it is added here).
    using S = refraction::Settings;
    struct Case {
        const char* value;
        std::function<bool(const S&)> decoded;
    };
    const std::map<std::string, Case> cases = {
        {"method", {"isr", [](const S& s) { return s.method == S::Method::Isr; }}},
        {"glass", {"all", [](const S& s) { return s.glass == S::Glass::All; }}},
        {"ior", {"1.33", [](const S& s) { return s.ior == 1.33; }}},
        {"dispersion", {"0.5", [](const S& s) { return s.dispersion == 0.5; }}},
        {"dispersion-search",
         {"per-channel",
          [](const S& s) { return s.dispersionSearch == S::DispersionSearch::PerChannel; }}},
        {"tint", {"0.5,0.25,1", [](const S& s) { return s.tint == glm::dvec3(0.5, 0.25, 1.0); }}},
        {"absorption-distance", {"2", [](const S& s) { return s.absorptionDistance == 2.0; }}},
        {"fresnel", {"schlick", [](const S& s) { return s.fresnel == S::Fresnel::Schlick; }}},
        {"search-steps", {"9", [](const S& s) { return s.searchSteps == 9; }}},
        {"tir", {"clamp", [](const S& s) { return s.tir == S::Tir::Clamp; }}},
        {"tir-bounces", {"3", [](const S& s) { return s.tirBounces == 3; }}},
        {"back-surface",
         {"first", [](const S& s) { return s.backSurface == S::BackSurface::First; }}},
        {"surfaces",
         {"two-surface", [](const S& s) { return s.surfaces == S::Surfaces::TwoSurface; }}},
        {"layer-capacity", {"6", [](const S& s) { return s.layerCapacity == 6; }}},
        {"interfaces", {"12", [](const S& s) { return s.interfaces == 12; }}},
        {"march-steps", {"20", [](const S& s) { return s.marchSteps == 20; }}},
        {"geometry-passes",
         {"two", [](const S& s) { return s.geometryPasses == S::GeometryPasses::Two; }}},
        {"trace-samples", {"16", [](const S& s) { return s.traceSamples == 16; }}},
        {"fresh-samples", {"8", [](const S& s) { return s.freshSamples == 8; }}},
        {"fresh-contrast", {"0.25", [](const S& s) { return s.freshContrast == 0.25; }}},
        {"hybrid-criteria", {"5", [](const S& s) { return s.hybridCriteria == 5; }}},
        {"nearby", {"off", [](const S& s) { return !s.nearby; }}},
        {"outline-aa", {"off", [](const S& s) { return !s.outlineAntialiasing; }}},
        {"glass-shadows", {"off", [](const S& s) { return !s.glassShadows; }}},
        {"caustics", {"off", [](const S& s) { return !s.caustics; }}},
        {"caustic-photons", {"64", [](const S& s) { return s.causticPhotons == 64000; }}},
        {"debug", {"steps", [](const S& s) { return s.debug == 6; }}}, // the seventh entry
    };
    for (const plugin::Parameter& parameter : S::parameterTable()) {
        ASSERT_TRUE(cases.count(parameter.name)) << parameter.name << " is not decoded here";
        auto glass = refraction::createPlugin();
        plugin::ParameterSet& p = glass->parameters();
        const Case& c = cases.at(parameter.name);
        EXPECT_FALSE(c.decoded(S::decode(p))) << parameter.name << ": the default already";
        ASSERT_TRUE(p.set(parameter.name, c.value).ok()) << parameter.name;
        EXPECT_TRUE(c.decoded(S::decode(p))) << parameter.name << "=" << c.value;
    }
    EXPECT_EQ(cases.size(), S::parameterTable().size());
}

TEST(Settings, EveryMethodDecodesWithWhatItNeeds) {
    // What each method runs: SIR one interface; ISR, DIR, the trace and the hybrid two and more;
    // ISR's d_N and the tracing methods' BVH; the capture's layers for all but opaque.
    using S = refraction::Settings;
    struct Expected {
        const char* method;
        S::Method decoded;
        bool twoInterfaces, traces, bvh, normalDistance, layered;
    };
    const Expected all[] = {{"opaque", S::Method::Opaque, false, false, false, false, false},
                            {"sir", S::Method::Sir, false, false, false, false, true},
                            {"isr", S::Method::Isr, true, false, true, true, true},
                            {"dir", S::Method::Dir, true, false, false, false, true},
                            {"trace", S::Method::Trace, true, true, true, false, true},
                            {"hybrid", S::Method::Hybrid, true, true, true, false, true}};
    auto glass = refraction::createPlugin();
    plugin::ParameterSet& p = glass->parameters();
    std::size_t choices = 0;
    for (const plugin::Parameter& parameter : S::parameterTable())
        if (parameter.name == "method")
            choices = parameter.choices.size();
    EXPECT_EQ(choices, std::size(all));
    for (const Expected& e : all) {
        ASSERT_TRUE(p.set("method", e.method).ok()) << e.method;
        const S s = S::decode(p);
        EXPECT_EQ(s.method, e.decoded) << e.method;
        EXPECT_EQ(s.twoInterfaces(), e.twoInterfaces) << e.method;
        EXPECT_EQ(s.traces(), e.traces) << e.method;
        EXPECT_EQ(s.usesGlassBvh(), e.bvh) << e.method;
        EXPECT_EQ(s.usesNormalDistance(), e.normalDistance) << e.method;
        EXPECT_EQ(s.layered(), e.layered) << e.method;
    }
}

TEST(Settings, GlassFollowsMethodAndSelection) {
    auto glass = refraction::createPlugin();
    plugin::ParameterSet& p = glass->parameters();
    scene::Model model;
    model.materials.resize(2);
    model.materials[1].hasTransmission = true;
    model.materials[1].transmissionFactor = 1.0f;
    ASSERT_TRUE(model.materials[1].isTransmissive());
    const int plain = 0, transmissive = 1;
    using S = refraction::Settings;
    EXPECT_FALSE(S::decode(p).isGlass(model, plain));
    EXPECT_TRUE(S::decode(p).isGlass(model, transmissive));
    ASSERT_TRUE(p.set("glass", "all").ok());
    EXPECT_TRUE(S::decode(p).isGlass(model, plain));
    ASSERT_TRUE(p.set("method", "opaque").ok());
    EXPECT_FALSE(S::decode(p).isGlass(model, transmissive));
}

} // namespace
