// Keyframe sampling (glTF §3.11 Animations): STEP, LINEAR (shortest-arc slerp for rotations),
// CUBICSPLINE (Hermite with tangents scaled by the key interval). No GL.
#pragma once

#include "engine/scene/Animation.h"

#include <glm/gtc/quaternion.hpp>

#include <span>

namespace anim {

/** Samples `sampler` at `time` seconds into `out` (sampler.components values). Times before the
 *  first key or after the last clamp to that key. When `isRotation`, the values are an xyzw
 *  quaternion: LINEAR slerps along the shorter arc and every result is normalised. */
void sample(const scene::AnimationSampler& sampler, double time, bool isRotation,
            std::span<double> out);

/** Shortest-arc spherical interpolation of unit quaternions; result normalised. */
glm::dquat slerpShortest(const glm::dquat& a, const glm::dquat& b, double s);

} // namespace anim
