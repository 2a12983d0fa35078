// Keyframe interpolation for the three glTF modes.
#include "engine/anim/Sampler.h"

#include "engine/core/Check.h"

#include <algorithm>
#include <cmath>

namespace anim {
namespace {

glm::dquat toQuat(const double* v) {
    return glm::dquat(v[3], v[0], v[1], v[2]);
}

void fromQuat(const glm::dquat& q, std::span<double> out) {
    out[0] = q.x;
    out[1] = q.y;
    out[2] = q.z;
    out[3] = q.w;
}

void normaliseQuat(std::span<double> v) {
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    if (length > 0.0)
        for (double& c : v)
            c /= length;
}

} // namespace

glm::dquat slerpShortest(const glm::dquat& a, const glm::dquat& b, double s) {
    glm::dquat end = b;
    double cosTheta = glm::dot(a, b);
    if (cosTheta < 0.0) {
        end = -b;
        cosTheta = -cosTheta;
    }
    if (cosTheta > 0.99995) // nearly parallel: lerp is exact to double precision here
        return glm::normalize(a * (1.0 - s) + end * s);
    const double theta = std::acos(std::min(cosTheta, 1.0));
    const double sinTheta = std::sin(theta);
    return glm::normalize(a * (std::sin((1.0 - s) * theta) / sinTheta) +
                          end * (std::sin(s * theta) / sinTheta));
}

void sample(const scene::AnimationSampler& sampler, double time, bool isRotation,
            std::span<double> out) {
    const std::size_t comps = std::size_t(sampler.components);
    ENGINE_CHECK(out.size() == comps, "output span must hold sampler.components values");
    ENGINE_CHECK(!sampler.times.empty(), "sampler has no keys");
    const bool cubic = sampler.interpolation == scene::Interpolation::CubicSpline;
    const std::size_t stride = cubic ? 3 * comps : comps;
    const std::size_t valueOffset = cubic ? comps : 0; // cubic: in-tangent, value, out-tangent
    const auto& t = sampler.times;
    const float* v = sampler.values.data();
    auto keyValue = [&](std::size_t k) { return v + k * stride + valueOffset; };

    const std::size_t last = t.size() - 1;
    std::size_t k = 0;
    if (time >= double(t[last])) {
        k = last;
    } else if (time > double(t[0])) {
        // First key strictly after `time`, minus one: t[k] <= time < t[k+1].
        k = std::size_t(std::upper_bound(t.begin(), t.end(), float(time)) - t.begin()) - 1;
        if (double(t[k]) > time) // float rounding of `time`
            k = k > 0 ? k - 1 : 0;
    }
    if (time <= double(t[0]) || k == last || sampler.interpolation == scene::Interpolation::Step) {
        const float* value = keyValue(k);
        for (std::size_t c = 0; c < comps; ++c)
            out[c] = double(value[c]);
        if (isRotation)
            normaliseQuat(out);
        return;
    }

    const double t0 = double(t[k]), t1 = double(t[k + 1]);
    const double dt = t1 - t0;
    const double s = dt > 0.0 ? std::clamp((time - t0) / dt, 0.0, 1.0) : 1.0;
    if (sampler.interpolation == scene::Interpolation::Linear) {
        const float* a = keyValue(k);
        const float* b = keyValue(k + 1);
        if (isRotation) {
            const double qa[4] = {a[0], a[1], a[2], a[3]}, qb[4] = {b[0], b[1], b[2], b[3]};
            fromQuat(slerpShortest(toQuat(qa), toQuat(qb), s), out);
            return;
        }
        for (std::size_t c = 0; c < comps; ++c)
            out[c] = double(a[c]) + (double(b[c]) - double(a[c])) * s;
        return;
    }

    // CUBICSPLINE (glTF Appendix C): Hermite basis, tangents scaled by the key interval.
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
    const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    const float* p0 = keyValue(k);
    const float* m0 = v + k * stride + 2 * comps; // out-tangent of key k
    const float* p1 = keyValue(k + 1);
    const float* m1 = v + (k + 1) * stride; // in-tangent of key k+1
    for (std::size_t c = 0; c < comps; ++c)
        out[c] = h00 * double(p0[c]) + h10 * dt * double(m0[c]) + h01 * double(p1[c]) +
                 h11 * dt * double(m1[c]);
    if (isRotation)
        normaliseQuat(out);
}

} // namespace anim
