// A character's clock, a world's longest clip; a world of one character.
#include "engine/scene/World.h"

#include <algorithm>
#include <cmath>

namespace scene {

int Character::playingClip() const {
    return model && clip >= 0 && clip < int(model->animations.size()) ? clip : -1;
}

double Character::clipPeriod() const {
    const int playing = playingClip();
    return playing < 0 || speed == 0.0
               ? 0.0
               : model->animations[std::size_t(playing)].duration / std::abs(speed);
}

double World::longestClipPeriod() const {
    double longest = 0.0;
    for (const Character& c : characters)
        longest = std::max(longest, c.clipPeriod());
    return longest;
}

double Character::clipTime(double sceneTime) const {
    if (playingClip() < 0)
        return 0.0;
    const double duration = model->animations[std::size_t(clip)].duration;
    const double t = (sceneTime + timeOffset) * speed;
    if (duration <= 0.0)
        return 0.0;
    if (!loop)
        return std::clamp(t, 0.0, duration);
    const double wrapped = std::fmod(t, duration);
    return wrapped < 0.0 ? wrapped + duration : wrapped;
}

World singleCharacterWorld(std::shared_ptr<const Model> model, int clip, std::string path) {
    Character c;
    c.name = path.empty() ? "character" : path.substr(path.find_last_of('/') + 1);
    c.model = std::move(model);
    c.modelPath = std::move(path);
    c.clip = clip;
    World world;
    world.characters.push_back(std::move(c));
    return world;
}

} // namespace scene
