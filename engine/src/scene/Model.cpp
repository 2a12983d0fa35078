// Scene-graph queries over an engine-owned model.
#include "engine/scene/Model.h"

#include <glm/gtc/matrix_transform.hpp>

#include <charconv>

namespace scene {

glm::dmat4 Trs::matrix() const {
    glm::dmat4 m = glm::mat4_cast(rotation);
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = glm::dvec4(translation, 1.0);
    return m;
}

const char* toString(Interpolation interpolation) {
    switch (interpolation) {
    case Interpolation::Step:
        return "STEP";
    case Interpolation::Linear:
        return "LINEAR";
    case Interpolation::CubicSpline:
        return "CUBICSPLINE";
    }
    return "?";
}

PointerObject objectOf(PointerProperty property) {
    if (property >= PointerProperty::CameraYfov)
        return PointerObject::Camera;
    if (property >= PointerProperty::LightColor)
        return PointerObject::Light;
    return PointerObject::Material;
}

int componentCount(PointerProperty property) {
    switch (property) {
    case PointerProperty::BaseColor:
        return 4;
    case PointerProperty::Emissive:
    case PointerProperty::AttenuationColor:
    case PointerProperty::LightColor:
        return 3;
    case PointerProperty::TextureOffset:
    case PointerProperty::TextureScale:
        return 2;
    default:
        return 1;
    }
}

const char* toString(AnimationPath path) {
    switch (path) {
    case AnimationPath::Translation:
        return "translation";
    case AnimationPath::Rotation:
        return "rotation";
    case AnimationPath::Scale:
        return "scale";
    case AnimationPath::Weights:
        return "weights";
    case AnimationPath::Pointer:
        return "pointer";
    }
    return "?";
}

std::vector<int> Model::sceneRoots() const {
    if (defaultScene >= 0 && defaultScene < int(scenes.size()))
        return scenes[std::size_t(defaultScene)];
    std::vector<int> roots;
    for (int i = 0; i < int(nodes.size()); ++i)
        if (nodes[std::size_t(i)].parent < 0)
            roots.push_back(i);
    return roots;
}

std::vector<int> Model::sceneNodes() const {
    // The loader guarantees a forest (no cycles, one parent each), so this terminates.
    std::vector<int> order;
    std::vector<int> stack;
    const std::vector<int> roots = sceneRoots();
    stack.assign(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
        const int node = stack.back();
        stack.pop_back();
        order.push_back(node);
        const auto& children = nodes[std::size_t(node)].children;
        stack.insert(stack.end(), children.rbegin(), children.rend());
    }
    return order;
}

std::vector<int> Model::cameraNodes() const {
    std::vector<int> found;
    for (int node : sceneNodes()) {
        const int camera = nodes[std::size_t(node)].camera;
        if (camera >= 0 && cameras[std::size_t(camera)].type == Camera::Type::Perspective)
            found.push_back(node);
    }
    return found;
}

std::vector<int> Model::meshNodes() const {
    std::vector<int> result;
    for (int node : sceneNodes())
        if (nodes[std::size_t(node)].mesh >= 0)
            result.push_back(node);
    return result;
}

namespace {

/** The index of the name `nameOrIndex` among `count` names (`nameOf(i)`), or of the index it
 *  spells when no name matches. */
template <class NameOf>
std::optional<int> findNamed(std::size_t count, NameOf nameOf, std::string_view nameOrIndex) {
    for (std::size_t i = 0; i < count; ++i)
        if (nameOf(i) == nameOrIndex)
            return int(i);
    int index = -1;
    const char* end = nameOrIndex.data() + nameOrIndex.size();
    const auto [ptr, ec] = std::from_chars(nameOrIndex.data(), end, index);
    if (ec == std::errc() && ptr == end && index >= 0 && index < int(count))
        return index;
    return std::nullopt;
}

} // namespace

std::optional<int> Model::findVariant(std::string_view nameOrIndex) const {
    return findNamed(
        variants.size(), [&](std::size_t i) -> const std::string& { return variants[i]; },
        nameOrIndex);
}

std::optional<int> Model::findAnimation(std::string_view nameOrIndex) const {
    return findNamed(
        animations.size(), [&](std::size_t i) -> const std::string& { return animations[i].name; },
        nameOrIndex);
}

} // namespace scene
