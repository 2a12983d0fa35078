// Plugin parameters: declaration, typed parsing, ranges, errors, presets.
#include "engine/plugin/ParameterSet.h"

#include <gtest/gtest.h>

namespace {

plugin::ParameterSet make() {
    plugin::ParameterSet p;
    p.declare({"ior", "IOR", plugin::Parameter::Type::Float, 1.0, 3.0, 1.5, {}, ""});
    p.declare({"steps", "Steps", plugin::Parameter::Type::Int, 1, 16, 5, {}, ""});
    p.declare({"nearby", "Nearby", plugin::Parameter::Type::Bool, 0, 1, 1, {}, ""});
    p.declare(
        {"method", "Method", plugin::Parameter::Type::Enum, 0, 0, 2, {"opaque", "sir", "dir"}, ""});
    return p;
}

TEST(ParameterSet, DefaultsAndTextRoundTrip) {
    auto p = make();
    EXPECT_DOUBLE_EQ(p.number("ior"), 1.5);
    EXPECT_EQ(p.choice("method"), "dir");
    EXPECT_TRUE(p.flag("nearby"));
    ASSERT_TRUE(p.set("ior", "1.33").ok());
    ASSERT_TRUE(p.set("steps", "8").ok());
    ASSERT_TRUE(p.set("nearby", "off").ok());
    ASSERT_TRUE(p.set("method", "sir").ok());
    EXPECT_EQ(p.text("ior"), "1.33");
    EXPECT_EQ(p.text("steps"), "8");
    EXPECT_EQ(p.text("nearby"), "off");
    EXPECT_EQ(p.text("method"), "sir");
}

TEST(ParameterSet, RejectsBadValuesNamingTheParameter) {
    auto p = make();
    auto s = p.set("ior", "0.5");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "parameter 'ior' must lie in [1, 3], got 0.5");
    s = p.set("steps", "2.5");
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("integer"), std::string::npos);
    s = p.set("method", "isr");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "parameter 'method' takes opaque|sir|dir, got 'isr'");
    s = p.set("colour", "red");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "unknown parameter 'colour' (known: ior, steps, nearby, method)");
    s = p.set("nearby", "maybe");
    ASSERT_FALSE(s.ok());
    EXPECT_DOUBLE_EQ(p.number("ior"), 1.5); // failed sets change nothing
}

TEST(ParameterSet, SetNumberClamps) {
    auto p = make();
    p.setNumber("ior", 9.0);
    EXPECT_DOUBLE_EQ(p.number("ior"), 3.0);
    p.setNumber("method", 7.0);
    EXPECT_EQ(p.choice("method"), "dir");
}

TEST(ParameterSet, RevisionChangesWithEveryValueSet) {
    auto p = make();
    const auto start = p.revision();
    ASSERT_FALSE(p.set("ior", "9").ok());
    EXPECT_EQ(p.revision(), start); // a refused value changes nothing
    ASSERT_TRUE(p.set("ior", "1.4").ok());
    const auto afterSet = p.revision();
    EXPECT_NE(afterSet, start);
    p.setNumber("steps", 3.0);
    EXPECT_NE(p.revision(), afterSet);
}

TEST(ParameterSet, PresetSetsAllItsValues) {
    auto p = make();
    ASSERT_TRUE(p.addPreset({"water", {{"ior", "1.333"}, {"method", "sir"}}}).ok());
    ASSERT_EQ(p.presets().size(), 1u);
    EXPECT_DOUBLE_EQ(p.number("ior"), 1.5); // adding one changes nothing yet
    ASSERT_TRUE(p.applyPreset("water").ok());
    EXPECT_DOUBLE_EQ(p.number("ior"), 1.333);
    EXPECT_EQ(p.choice("method"), "sir");
    EXPECT_EQ(p.number("steps"), 5.0); // values the preset does not name stay
}

TEST(ParameterSet, PresetsAreCheckedWhenAdded) {
    auto p = make();
    auto s = p.addPreset({"lead glass", {{"ior", "1.6"}, {"steps", "40"}}});
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "preset 'lead glass': parameter 'steps' must lie in [1, 16], got 40");
    s = p.addPreset({"ghost", {{"opacity", "0"}}});
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("preset 'ghost': unknown parameter 'opacity'"),
              std::string::npos);
    EXPECT_TRUE(p.presets().empty());
    EXPECT_DOUBLE_EQ(p.number("ior"), 1.5); // a refused preset set nothing
    ASSERT_TRUE(p.addPreset({"water", {{"ior", "1.333"}}}).ok());
    s = p.addPreset({"water", {{"ior", "1.34"}}});
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "preset 'water' declared twice");
    s = p.applyPreset("oil");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "unknown preset 'oil' (known: water)");
}

} // namespace
