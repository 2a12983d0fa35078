// render::LightingFeatures: which parts of the lighting a frame's programs compile.
#include "engine/render/LightingFeatures.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace {

scene::PlacedLight light(float softness,
                         scene::Light::Type type = scene::Light::Type::Directional) {
    scene::PlacedLight l;
    l.light.type = type;
    l.light.shadow.softness = softness;
    return l;
}

/** A plan in which the lights at `casting` cast (one view each). */
render::ShadowPlan plan(std::size_t lights, std::initializer_list<std::size_t> casting) {
    render::ShadowPlan p;
    p.firstView.assign(lights, -1);
    for (std::size_t i : casting) {
        p.firstView[i] = int(p.views.size());
        p.views.emplace_back();
    }
    return p;
}

bool has(const std::vector<std::string>& defines, const std::string& define) {
    return std::find(defines.begin(), defines.end(), define) != defines.end();
}

TEST(LightingFeatures, AFrameWithoutLightsCompilesNoneOfTheirParts) {
    const auto f = render::LightingFeatures::of({}, plan(0, {}), true, true);
    EXPECT_EQ(f, render::LightingFeatures{});
    for (const char* define :
         {"PUNCTUAL_LIGHTS 0", "DIRECTIONAL_LIGHTS 0", "POINT_LIGHTS 0", "SPOT_LIGHTS 0",
          "SHADOW_MAPS 0", "SHADOW_SOFT 0", "SHADOW_GLASS 0", "SHADOW_CAUSTICS 0"})
        EXPECT_TRUE(has(f.defines(), define)) << define;
}

TEST(LightingFeatures, ShadowPartsFollowTheLightsThatCast) {
    const std::vector<scene::PlacedLight> lights{light(1.5f), light(0.0f)};
    // Lights, none casting: the shadow lookup is out, whatever the plugins drew.
    auto f = render::LightingFeatures::of(lights, plan(2, {}), true, true);
    EXPECT_TRUE(f.lights);
    EXPECT_FALSE(f.shadowMaps || f.softShadows || f.glassShadows || f.caustics);
    // The hard light casts: one tap; the soft one: the filter.
    f = render::LightingFeatures::of(lights, plan(2, {1}), false, false);
    EXPECT_TRUE(f.shadowMaps);
    EXPECT_FALSE(f.softShadows);
    f = render::LightingFeatures::of(lights, plan(2, {0, 1}), true, false);
    EXPECT_TRUE(f.softShadows && f.glassShadows);
    EXPECT_FALSE(f.caustics);
    EXPECT_TRUE(has(f.defines(), "SHADOW_GLASS 1"));
    EXPECT_TRUE(has(f.defines(), "SHADOW_CAUSTICS 0"));
}

TEST(LightingFeatures, EachTypeOfLightCompilesOnlyWhereTheFrameHasOne) {
    using Type = scene::Light::Type;
    auto f = render::LightingFeatures::of(std::vector{light(0.0f)}, plan(1, {}), false, false);
    EXPECT_TRUE(f.directional);
    EXPECT_FALSE(f.point || f.spot);
    EXPECT_TRUE(has(f.defines(), "DIRECTIONAL_LIGHTS 1"));
    EXPECT_TRUE(has(f.defines(), "POINT_LIGHTS 0"));
    EXPECT_TRUE(has(f.defines(), "SPOT_LIGHTS 0"));
    f = render::LightingFeatures::of(std::vector{light(0.0f, Type::Spot), light(0.0f, Type::Point)},
                                     plan(2, {}), false, false);
    EXPECT_FALSE(f.directional);
    EXPECT_TRUE(f.point && f.spot);
}

} // namespace
