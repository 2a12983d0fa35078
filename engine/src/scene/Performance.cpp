// A performance's clocks: layer time mapping (repeat, clamp, ping-pong, repetitions), the held
// time of a paused character, and the period a viewer's clock wraps at.
#include "engine/scene/Performance.h"

#include "engine/scene/Model.h"

#include <algorithm>
#include <cmath>

namespace scene {
namespace {

/** The time `t` of an endless ping-pong over [0, duration]: forward, backward, forward... */
double pingPong(double t, double duration) {
    double phase = std::fmod(t, 2.0 * duration);
    if (phase < 0.0)
        phase += 2.0 * duration;
    return duration - std::abs(phase - duration);
}

} // namespace

double Layer::clipTime(double time, double duration) const {
    if (duration <= 0.0)
        return 0.0;
    double t = (time + timeOffset) * speed;
    switch (loop) {
    case Loop::Clamp:
        return std::clamp(t, 0.0, duration);
    case Loop::PingPong:
        if (repetitions > 0)
            t = std::clamp(t, -repetitions * duration, repetitions * duration);
        return pingPong(t, duration);
    case Loop::Repeat:
        break;
    }
    if (repetitions > 0 && std::abs(t) >= repetitions * duration)
        return t > 0.0 ? duration : 0.0; // the last frame of the last run
    const double wrapped = std::fmod(t, duration);
    return wrapped < 0.0 ? wrapped + duration : wrapped;
}

long long Layer::completedLoops(double time, double duration) const {
    if (loop != Loop::Repeat || duration <= 0.0)
        return 0;
    const double runs = std::floor((time + timeOffset) * speed / duration);
    if (repetitions > 0)
        return (long long)std::clamp(runs, -double(repetitions), double(repetitions - 1));
    // Beyond 2^53 loops the clock has no resolution left anyway.
    return (long long)std::clamp(runs, -9.0e15, 9.0e15);
}

Performance Performance::single(int clip) {
    Performance p;
    p.layers.emplace_back().clip = clip;
    return p;
}

void Performance::shift(double seconds) {
    for (Layer& layer : layers)
        layer.timeOffset += seconds;
    for (Transition& transition : transitions)
        transition.at -= seconds;
}

double Performance::characterTime(double sceneTime) const {
    if (!pausedAt)
        return sceneTime;
    if (layers.empty())
        return *pausedAt;
    const Layer& first = layers.front();
    return (first.speed != 0.0 ? *pausedAt / first.speed : *pausedAt) - first.timeOffset;
}

int Performance::mainClip(const scene::Model& model) const {
    if (layers.empty())
        return -1;
    const int clip = layers.front().clip;
    return clip >= 0 && clip < int(model.animations.size()) ? clip : -1;
}

double Performance::period(const scene::Model& model) const {
    if (pausedAt)
        return 0.0;
    const int clip = mainClip(model);
    return clip < 0 || layers.front().speed == 0.0
               ? 0.0
               : model.animations[std::size_t(clip)].duration / std::abs(layers.front().speed);
}

bool Performance::repeats() const {
    return transitions.empty() && rootMotion != RootMotion::Accumulate;
}

double Performance::lastChange() const {
    double last = 0.0;
    for (const Transition& t : transitions)
        last = std::max(last, t.at + t.duration);
    return last;
}

const char* toString(Loop loop) {
    switch (loop) {
    case Loop::Repeat:
        return "repeat";
    case Loop::Clamp:
        return "clamp";
    case Loop::PingPong:
        return "ping_pong";
    }
    return "?";
}

const char* toString(RootMotion rootMotion) {
    switch (rootMotion) {
    case RootMotion::Baked:
        return "baked";
    case RootMotion::InPlace:
        return "in_place";
    case RootMotion::Accumulate:
        return "accumulate";
    }
    return "?";
}

} // namespace scene
