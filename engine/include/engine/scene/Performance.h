// What a character plays, as declared data: clip layers, each on its own clock, scheduled
// crossfades, root motion and morph-weight settings. The pose is a function of a performance and
// the scene time alone (anim::evaluate), so every frame, capture and reference agrees. No GL.
#pragma once

#include <optional>
#include <vector>

namespace scene {

struct Model;

/** How a layer's clock maps past the clip's ends. */
enum class Loop {
    Repeat,   ///< wraps around
    Clamp,    ///< holds the first and last frames
    PingPong, ///< plays forward, then backward, and so on
};

/** How a clip's root travel (the horizontal movement of the shallowest translated joint) plays.
 */
enum class RootMotion {
    Baked,      ///< as the clip has it: a looping walk jumps back every loop
    InPlace,    ///< held at the clip's first frame horizontally: the character walks on the spot
    Accumulate, ///< each loop starts where the last ended: the walker walks on
};

/** A joint subtree a masked layer drives, with the weight it drives it at. A deeper entry
 *  overrides its ancestors'; nodes under no entry are not driven. */
struct MaskEntry {
    int node = -1; ///< index into Model::nodes
    double weight = 1.0;
    bool operator==(const MaskEntry&) const = default;
};

/** One clip playing on its own clock. */
struct Layer {
    int clip = -1;           ///< index into Model::animations; -1: plays nothing
    double weight = 1.0;     ///< blend weight (>= 0)
    double timeOffset = 0.0; ///< seconds added to the character's time
    double speed = 1.0;      ///< clip seconds per character second (negative plays backwards)
    Loop loop = Loop::Repeat;
    /** Runs through the clip (each way of a ping-pong is one) before the layer holds its last
     *  frame; 0: no end. Clamp ignores it. */
    int repetitions = 0;
    /** Adds the clip's change from its first frame on top of the layers under it, rather than
     *  blending toward the clip's pose. */
    bool additive = false;
    std::vector<MaskEntry> mask; ///< empty: every node

    /** The clip time, in [0, duration], at `time` character seconds. */
    double clipTime(double time, double duration) const;
    /** Whole runs through the clip completed at `time` (negative when playing backwards), for
     *  accumulated root motion: the count of wraps of a Repeat layer, else 0. */
    long long completedLoops(double time, double duration) const;
    bool operator==(const Layer&) const = default;
};

/** At `at` character seconds, crossfade from everything the character plays without addition
 *  to clip `to` over `duration` seconds: the weights move linearly, and `to` starts at its own
 *  time 0 at `at` and repeats (three.js's crossFadeTo with warp off). */
struct Transition {
    double at = 0.0;
    int to = -1;
    double duration = 0.0;
    bool operator==(const Transition&) const = default;
};

/** A morph target's weight set on every node whose mesh is `mesh` (or on every morphing node for
 *  -1), replacing the clip's (or the file's) weight or added to it. */
struct MorphSetting {
    int mesh = -1;
    int target = 0;
    double value = 0.0;
    bool add = false;
    bool operator==(const MorphSetting&) const = default;
};

struct Performance {
    std::vector<Layer> layers;
    std::vector<Transition> transitions; ///< sorted by `at`
    RootMotion rootMotion = RootMotion::Baked;
    std::vector<MorphSetting> morphs;
    /** A clip time the character holds while the scene plays: the character's clock stops
     *  where its first layer shows this clip time. */
    std::optional<double> pausedAt;

    /** One layer playing `clip` (-1: the rest pose) from time 0, repeating. */
    static Performance single(int clip);

    /** Plays `seconds` ahead: every layer's clock and every transition moved by that much. */
    void shift(double seconds);

    /** The character's time at scene time `sceneTime`: the scene time, or the held time. */
    double characterTime(double sceneTime) const;
    /** The first layer's clip when it names one of `model`'s clips, else -1. */
    int mainClip(const scene::Model& model) const;
    /** The clip the performance ends on: the last transition's, else the first layer's. */
    int finalClip() const {
        return !transitions.empty() ? transitions.back().to
               : layers.empty()     ? -1
                                    : layers.front().clip;
    }
    /** Scene seconds one run of the first layer takes (its clip's duration over |speed|); 0
     *  without a clip, at speed 0 or while paused. The pose repeats with it where repeats(). */
    double period(const scene::Model& model) const;
    /** False where the pose never comes back: after transitions, or walking on (accumulated
     *  root motion). */
    bool repeats() const;
    /** The character time the last transition ends at; 0 without transitions. */
    double lastChange() const;
    bool operator==(const Performance&) const = default;
};

const char* toString(Loop loop);
const char* toString(RootMotion rootMotion);

} // namespace scene
