// A character's transform and clock.
#include "engine/scene/World.h"

#include <algorithm>
#include <cmath>

namespace scene {

glm::mat4 Character::transform() const {
    glm::mat4 m = glm::mat4_cast(rotation);
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = glm::vec4(translation, 1.0f);
    return m;
}

double Character::clipTime(double sceneTime) const {
    if (!model || clip < 0 || clip >= int(model->animations.size()))
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

} // namespace scene
