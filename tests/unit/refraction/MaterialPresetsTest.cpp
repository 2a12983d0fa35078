// The refraction plugin's material presets: plain parameter data, no GL and no UI library.
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

} // namespace
