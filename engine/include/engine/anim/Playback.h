// Playback state of one clip: which clip, where in it, how fast, looping or clamped. No GL.
#pragma once

namespace anim {

/** Advances a clip's time. Time is in seconds, in [0, duration]: looping wraps, clamping holds
 *  the last frame and stops. A negative speed plays backwards. */
struct Playback {
    int clip = -1; ///< index into Model::animations; -1 plays nothing (rest pose)
    double time = 0.0;
    double speed = 1.0;
    bool loop = true;
    bool playing = true;

    /** Moves time by dt * speed seconds (when playing) within a clip of `duration` seconds. */
    void advance(double dt, double duration);
};

} // namespace anim
