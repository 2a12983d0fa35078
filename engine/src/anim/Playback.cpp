// Clip time advance: loop or clamp.
#include "engine/anim/Playback.h"

#include <cmath>

namespace anim {

void Playback::advance(double dt, double duration) {
    if (!playing || clip < 0)
        return;
    time += dt * speed;
    if (!(duration > 0.0)) {
        time = 0.0;
        return;
    }
    if (loop) {
        time = std::fmod(time, duration);
        if (time < 0.0)
            time += duration;
    } else if (time >= duration || time <= 0.0) {
        time = time >= duration ? duration : 0.0;
        playing = false;
    }
}

} // namespace anim
