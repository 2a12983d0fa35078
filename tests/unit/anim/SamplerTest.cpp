// Keyframe sampling against hand-computed values, one case per interpolation mode.
#include "engine/anim/Sampler.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace {

scene::AnimationSampler makeSampler(scene::Interpolation mode, std::vector<float> times,
                                    std::vector<float> values, int components) {
    scene::AnimationSampler s;
    s.interpolation = mode;
    s.times = std::move(times);
    s.values = std::move(values);
    s.components = components;
    return s;
}

double sample1(const scene::AnimationSampler& s, double t) {
    double v = 0.0;
    anim::sample(s, t, false, std::span(&v, 1));
    return v;
}

TEST(Sampler, StepHoldsTheEarlierKey) {
    const auto s = makeSampler(scene::Interpolation::Step, {0, 1, 2}, {0, 10, 20}, 1);
    EXPECT_EQ(sample1(s, -1.0), 0.0);
    EXPECT_EQ(sample1(s, 0.5), 0.0);
    EXPECT_EQ(sample1(s, 1.0), 10.0);
    EXPECT_EQ(sample1(s, 1.999), 10.0);
    EXPECT_EQ(sample1(s, 5.0), 20.0);
}

TEST(Sampler, LinearInterpolatesVectors) {
    const auto s = makeSampler(scene::Interpolation::Linear, {0, 2}, {0, 0, 0, 2, 4, 6}, 3);
    std::array<double, 3> v{};
    anim::sample(s, 0.5, false, v);
    EXPECT_DOUBLE_EQ(v[0], 0.5);
    EXPECT_DOUBLE_EQ(v[1], 1.0);
    EXPECT_DOUBLE_EQ(v[2], 1.5);
}

TEST(Sampler, LinearRotationSlerpsAlongTheShorterArc) {
    const double h = std::sqrt(0.5);
    // 0 -> 90 degrees about z; the second key is stored negated (same rotation, far hemisphere).
    const auto s = makeSampler(scene::Interpolation::Linear, {0, 1},
                               {0, 0, 0, 1, 0, 0, float(-h), float(-h)}, 4);
    std::array<double, 4> q{};
    anim::sample(s, 0.5, true, q);
    // 45 degrees about z: (0, 0, sin 22.5, cos 22.5), up to sign.
    const double sign = q[3] < 0 ? -1.0 : 1.0;
    EXPECT_NEAR(sign * q[2], std::sin(M_PI / 8), 1e-7);
    EXPECT_NEAR(sign * q[3], std::cos(M_PI / 8), 1e-7);
    anim::sample(s, 0.25, true, q);
    EXPECT_NEAR(std::abs(q[2]), std::sin(M_PI / 16), 1e-7);
}

TEST(Sampler, CubicSplineScalesTangentsByKeyInterval) {
    // Keys at t=0 (value 0, out-tangent 1) and t=2 (in-tangent -1, value 1); dt = 2.
    // At t=0.5: s=0.25, h00=0.84375, h10=0.140625, h01=0.15625, h11=-0.046875;
    // value = 0.140625*2*1 + 0.15625*1 + (-0.046875)*2*(-1) = 0.53125.
    const auto s = makeSampler(scene::Interpolation::CubicSpline, {0, 2},
                               {/*in*/ 0, /*v*/ 0, /*out*/ 1, /*in*/ -1, /*v*/ 1, /*out*/ 0}, 1);
    EXPECT_NEAR(sample1(s, 0.5), 0.53125, 1e-12);
    EXPECT_NEAR(sample1(s, 0.0), 0.0, 1e-12);
    EXPECT_NEAR(sample1(s, 2.0), 1.0, 1e-12);
    EXPECT_NEAR(sample1(s, 9.0), 1.0, 1e-12);
}

TEST(Sampler, CubicSplineRotationIsNormalised) {
    const auto s =
        makeSampler(scene::Interpolation::CubicSpline, {0, 1},
                    {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0}, 4);
    std::array<double, 4> q{};
    anim::sample(s, 0.5, true, q);
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-12);
    EXPECT_NEAR(q[2], std::sqrt(0.5), 1e-12); // Hermite midpoint (0,0,.5,.5), normalised
}

} // namespace
