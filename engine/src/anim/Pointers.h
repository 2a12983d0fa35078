// KHR_animation_pointer properties in the blend: a material's, light's or camera's property
// blended as a node's is, then written into the pose's copies of the model's lists.
#pragma once

#include "engine/anim/Pose.h"

namespace anim::detail {

/** Clears the pointer blend of the last evaluation. */
void resetPointers(Pose& pose);

/** Blends the sample of pointer channel `channel` at `clipTime` into its property with `weight`:
 *  a running weighted average, or, for an additive layer, its change from the clip's first
 *  frame. */
void addPointer(const scene::AnimationChannel& channel, const scene::AnimationSampler& sampler,
                double clipTime, double weight, bool additive, Pose& pose);

/** The pose's materials, lights and cameras with the blended properties: the rest value fills
 *  weights under one, additive sums go on top. A list stays empty when nothing of its kind
 *  played. */
void finishPointers(const scene::Model& model, Pose& pose);

} // namespace anim::detail
