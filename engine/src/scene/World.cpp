// A world's periods and timeline; a world of one character.
#include "engine/scene/World.h"

#include <algorithm>
#include <cmath>

namespace scene {

double World::longestPeriod() const {
    double longest = 0.0;
    for (const Character& c : characters)
        longest = std::max(longest, c.period());
    return longest;
}

bool World::repeats() const {
    for (const Character& c : characters)
        if (!c.performance.repeats())
            return false;
    return true;
}

double World::timeline() const {
    double last = 0.0;
    for (const Character& c : characters)
        last = std::max(last, c.performance.lastChange());
    return last + longestPeriod();
}

World singleCharacterWorld(std::shared_ptr<const Model> model, int clip, std::string path) {
    Character c;
    c.name = path.empty() ? "character" : path.substr(path.find_last_of('/') + 1);
    c.model = std::move(model);
    c.modelPath = std::move(path);
    c.play(clip);
    World world;
    world.characters.push_back(std::move(c));
    return world;
}

} // namespace scene
