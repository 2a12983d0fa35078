// Engine-owned animation clips: keyframe samplers and the node properties they drive.
#pragma once

#include <string>
#include <vector>

namespace scene {

enum class Interpolation { Step, Linear, CubicSpline };
enum class AnimationPath { Translation, Rotation, Scale, Weights };

const char* toString(Interpolation interpolation);
const char* toString(AnimationPath path);

/** Keyframes: `times` strictly increasing (seconds); `values` holds `components` floats per
 *  element. CubicSpline stores three elements per key: in-tangent, value, out-tangent.
 *  Rotation values are xyzw quaternions, as in glTF. */
struct AnimationSampler {
    std::vector<float> times;
    std::vector<float> values;
    Interpolation interpolation = Interpolation::Linear;
    int components = 0; ///< 3 (translation, scale), 4 (rotation) or the morph-target count
};

struct AnimationChannel {
    int sampler = -1;
    int node = -1;
    AnimationPath path = AnimationPath::Translation;
};

/** A KHR_animation_pointer channel of the file: played (a node's TRS or weights, among the
 *  channels) or skipped (a pointer this engine does not play). */
struct PointerChannel {
    int channel = -1; ///< the file's index in the animation's channels
    std::string pointer;
    bool played = false;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;
    double duration = 0.0;                ///< last key time over all samplers, seconds
    std::vector<PointerChannel> pointers; ///< the file's pointer channels, in its order
};

} // namespace scene
