// The refraction plugin's parameters: decoded into Settings (what the passes and the reference
// read), and its material presets, plain parameter data with no GL and no UI library.
#include "Settings.h"
#include "refraction/RefractionPlugin.h"

#include <gtest/gtest.h>

#include <cmath>

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
    auto glass = refraction::createPlugin();
    plugin::ParameterSet& p = glass->parameters();
    using S = refraction::Settings;
    const S defaults = S::decode(p);
    EXPECT_EQ(defaults.method, S::Method::Dir);
    EXPECT_EQ(defaults.geometryPasses, S::GeometryPasses::One);
    EXPECT_TRUE(defaults.nearby);
    EXPECT_EQ(defaults.tir, S::Tir::Reflect); // as light does (and the reference)
    for (const auto& [key, value] : {std::pair{"method", "isr"},
                                     {"glass", "all"},
                                     {"ior", "1.33"},
                                     {"dispersion", "0.5"},
                                     {"tint", "0.5,0.25,1"},
                                     {"absorption-distance", "2"},
                                     {"fresnel", "schlick"},
                                     {"search-steps", "9"},
                                     {"tir", "clamp"},
                                     {"tir-bounces", "3"},
                                     {"back-surface", "first"},
                                     {"geometry-passes", "two"},
                                     {"dispersion-search", "per-channel"},
                                     {"nearby", "off"},
                                     {"debug", "steps"}})
        ASSERT_TRUE(p.set(key, value).ok()) << key;
    const S s = S::decode(p);
    EXPECT_EQ(s.method, S::Method::Isr);
    EXPECT_TRUE(s.twoInterfaces());
    EXPECT_EQ(s.glass, S::Glass::All);
    EXPECT_DOUBLE_EQ(s.ior, 1.33);
    EXPECT_DOUBLE_EQ(s.dispersion, 0.5);
    EXPECT_EQ(s.tint, glm::dvec3(0.5, 0.25, 1.0));
    EXPECT_DOUBLE_EQ(s.absorptionDistance, 2.0);
    EXPECT_EQ(s.fresnel, S::Fresnel::Schlick);
    EXPECT_EQ(s.searchSteps, 9);
    EXPECT_EQ(s.tir, S::Tir::Clamp);
    EXPECT_EQ(s.tirBounces, 3);
    EXPECT_EQ(s.backSurface, S::BackSurface::First);
    EXPECT_EQ(s.geometryPasses, S::GeometryPasses::Two);
    EXPECT_EQ(s.dispersionSearch, S::DispersionSearch::PerChannel);
    EXPECT_FALSE(s.nearby);
    EXPECT_EQ(s.debug, 6); // "steps" is the debug list's seventh entry
    ASSERT_TRUE(p.set("method", "sir").ok());
    EXPECT_FALSE(S::decode(p).twoInterfaces());
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
