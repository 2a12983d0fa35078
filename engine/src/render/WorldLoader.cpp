// Scene files, or models side by side.
#include "engine/render/WorldLoader.h"

#include "engine/asset/ModelLoader.h"
#include "engine/asset/SceneFile.h"
#include "engine/core/Limits.h"
#include "engine/render/Camera.h"

#include <algorithm>
#include <filesystem>
#include <map>

namespace render {

core::Result<scene::World> loadWorld(std::span<const std::string> paths,
                                     const asset::LoadOptions& options) {
    if (paths.empty())
        return core::Error{"render::loadWorld(): no model or scene file given"};
    const bool anyScene = std::any_of(paths.begin(), paths.end(),
                                      [](const std::string& p) { return asset::isSceneFile(p); });
    if (anyScene && paths.size() > 1)
        return core::Error{"render::loadWorld(): a scene file (" + paths[0] +
                           ", ...) cannot be mixed with other models or scenes: give one"};
    if (anyScene)
        return asset::loadScene(paths[0], options);
    if (paths.size() > core::limits::kMaxCharacters)
        return core::Error{"render::loadWorld(): " + std::to_string(paths.size()) +
                           " models, the limit is " + std::to_string(core::limits::kMaxCharacters) +
                           " characters"};

    scene::World world;
    std::map<std::string, std::shared_ptr<const scene::Model>> loaded;
    std::vector<Bounds> bounds;
    for (const std::string& path : paths) {
        auto& model = loaded[path];
        if (!model) {
            auto read = asset::loadModel(path, options);
            if (!read)
                return read.error();
            model = std::make_shared<const scene::Model>(std::move(*read));
        }
        scene::World one =
            scene::singleCharacterWorld(model, model->animations.empty() ? -1 : 0, path);
        if (path.rfind("builtin:", 0) != 0)
            one.characters[0].modelPath = std::filesystem::absolute(path).lexically_normal();
        if (paths.size() > 1) {
            // appended in two steps: `" " + std::to_string(...)` here trips GCC 12's -Wrestrict
            // false positive at -O3 (GCC bug 105329)
            one.characters[0].name += ' ';
            one.characters[0].name += std::to_string(world.characters.size() + 1);
            bounds.push_back(worldBounds(one));
        }
        world.characters.push_back(std::move(one.characters[0]));
        if (auto limits = asset::checkWorldLimits(world, "the models given"); !limits)
            return limits.error();
    }
    if (paths.size() > 1) {
        float widest = 0.0f, total = 0.0f;
        for (const Bounds& b : bounds) {
            widest = std::max(widest, b.max.x - b.min.x);
            total += b.max.x - b.min.x;
        }
        const float gap = 0.2f * widest;
        total += gap * float(bounds.size() - 1);
        float x = -0.5f * total;
        for (std::size_t i = 0; i < bounds.size(); ++i) {
            // Left edge of this one's bounds at x; its depth centred on z = 0.
            world.characters[i].placement.translation = glm::dvec3(
                x - bounds[i].min.x, 0.0, -0.5 * double(bounds[i].min.z + bounds[i].max.z));
            x += bounds[i].max.x - bounds[i].min.x + gap;
        }
    }
    return world;
}

} // namespace render
