// Engine-owned skin: the joints and their inverse bind matrices.
#pragma once

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace scene {

/** Joint j of a primitive's JOINTS_n refers to node joints[j]. inverseBind[j] maps mesh bind
 *  space to joint j's local space (identity when the file has none). */
struct Skin {
    std::string name;
    std::vector<int> joints;
    std::vector<glm::dmat4> inverseBind;
    int skeleton = -1;
};

} // namespace scene
