// A loaded model: everything asset::loadGltf produces, owned by the engine (no tinygltf types).
#pragma once

#include "engine/scene/Animation.h"
#include "engine/scene/Camera.h"
#include "engine/scene/Light.h"
#include "engine/scene/Material.h"
#include "engine/scene/Mesh.h"
#include "engine/scene/Node.h"
#include "engine/scene/Skin.h"
#include "engine/scene/Texture.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace scene {

struct Model {
    std::string sourceName; ///< file name, for messages
    std::vector<Node> nodes;
    std::vector<Mesh> meshes;
    std::vector<Skin> skins;
    std::vector<Animation> animations;
    std::vector<std::string> variants; ///< KHR_materials_variants' names, in the file's order
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Image> images;
    std::vector<Sampler> samplers;
    std::vector<Camera> cameras;
    std::vector<Light> lights; ///< KHR_lights_punctual, placed by the nodes that name them
    std::vector<std::vector<int>> scenes; ///< root nodes of each scene
    int defaultScene = 0;                 ///< -1 when the file has no scene
    /** What loading skipped or could not honour, each naming its element (an extension the
     *  engine does not implement, a primitive it does not draw); the model is usable without. */
    std::vector<std::string> warnings;

    /** Roots of the default scene (all parentless nodes when the file has no scene). */
    std::vector<int> sceneRoots() const;
    /** Nodes of the default scene in depth-first pre-order (parents before children). */
    std::vector<int> sceneNodes() const;
    /** Nodes of the default scene that carry a mesh, in sceneNodes() order. */
    std::vector<int> meshNodes() const;
    /** The default scene's nodes that hold a perspective camera. */
    std::vector<int> cameraNodes() const;
    /** Clip index by name, or by decimal index when `nameOrIndex` is a number. */
    std::optional<int> findAnimation(std::string_view nameOrIndex) const;
    /** The variant named `nameOrIndex` (KHR_materials_variants: a name, or an index). */
    std::optional<int> findVariant(std::string_view nameOrIndex) const;
};

} // namespace scene
