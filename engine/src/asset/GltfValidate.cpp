// Structural validation of a parsed glTF before any conversion: every index the engine follows
// is in range, the node graph is a forest, required extensions are supported, limits hold.
#include "GltfConvert.h"
#include "GltfDecode.h"

#include "LoadError.h"
#include "engine/asset/GltfLoader.h"
#include "engine/core/Limits.h"

#include <cstdio>
#include <string>
#include <utility>

namespace asset {

const std::set<std::string>& supportedRequiredExtensions() {
    static const std::set<std::string> supported = {
        "KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior",
        "KHR_materials_dispersion", "KHR_materials_emissive_strength", "KHR_draco_mesh_compression",
        "EXT_meshopt_compression", "KHR_meshopt_compression", "KHR_mesh_quantization",
        "KHR_texture_transform", "KHR_materials_unlit", "EXT_texture_webp",
        "KHR_materials_pbrSpecularGlossiness", "EXT_mesh_gpu_instancing", "KHR_materials_variants",
        "KHR_materials_specular", "KHR_materials_clearcoat", "KHR_materials_sheen",
        "KHR_materials_iridescence", "KHR_materials_anisotropy", "KHR_lights_punctual",
        // nodes, materials, texture transforms, lights and yfov play; others are skipped
        "KHR_animation_pointer",
        // only its fallback images are used; a texture with none loads without it (warning)
        "KHR_texture_basisu"};
    return supported;
}

} // namespace asset

namespace asset::detail {
namespace {

std::string n(std::size_t v) {
    return std::to_string(v);
}
std::string n(int v) {
    return std::to_string(v);
}

/** Fails unless -1 <= index < count ("-1" meaning absent is allowed when `optional`). */
void checkIndex(int index, std::size_t count, bool optional, const std::string& what,
                const char* kind, const char* plural) {
    if (optional && index == -1)
        return;
    if (index < 0 || std::size_t(index) >= count)
        fail(what + " references " + kind + " " + n(index) + ", file has " + n(count) + " " +
             plural);
}

void checkTexture(const tinygltf::Model& m, int texture, const std::string& what) {
    checkIndex(texture, m.textures.size(), true, what, "texture", "textures");
}

} // namespace

void checkVersion(const tinygltf::Asset& asset) {
    // "major.minor" (glTF 2.0 section 3.3.1); a file of another major version is another format.
    auto parse = [](const std::string& text, const char* key) {
        unsigned major = 0, minor = 0;
        char dot = 0, extra = 0;
        if (std::sscanf(text.c_str(), "%u%c%u%c", &major, &dot, &minor, &extra) != 3 || dot != '.')
            fail(std::string("asset.") + key + " \"" + text + "\" is not major.minor");
        return std::pair{major, minor};
    };
    const auto [major, minor] = parse(asset.version, "version");
    if (major != 2)
        fail("asset.version " + asset.version + ": glTF " + n(int(major)) +
             " is not glTF 2, which this engine reads");
    (void)minor; // a later 2.x is read as 2.0 unless minVersion says it cannot be
    if (!asset.minVersion.empty()) {
        const auto [minMajor, minMinor] = parse(asset.minVersion, "minVersion");
        if (minMajor != 2 || minMinor > 0)
            fail("asset.minVersion " + asset.minVersion +
                 ": the file needs a glTF newer than 2.0, which this engine reads");
    }
}

bool isMaterialExtension(const std::string& extension) { // GltfConvert.h
    return extension.rfind("KHR_materials_", 0) == 0;
}

namespace {

/** Node references, one parent per node, no cycle, scene roots that are roots. */
void checkHierarchy(const tinygltf::Model& m) {
    if (m.nodes.size() > core::limits::kMaxNodes)
        fail(n(m.nodes.size()) + " nodes, over the limit of " + n(core::limits::kMaxNodes));
    std::vector<int> parent(m.nodes.size(), -1);
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
        const tinygltf::Node& node = m.nodes[i];
        const std::string what = "node " + n(i);
        checkIndex(node.mesh, m.meshes.size(), true, what, "mesh", "meshes");
        checkIndex(node.skin, m.skins.size(), true, what, "skin", "skins");
        checkIndex(node.camera, m.cameras.size(), true, what, "camera", "cameras");
        if (!node.matrix.empty() && node.matrix.size() != 16)
            fail(what + " matrix has " + n(node.matrix.size()) + " values, expected 16");
        for (int child : node.children) {
            checkIndex(child, m.nodes.size(), false, what + " child", "node", "nodes");
            if (child == int(i))
                fail(what + " lists itself as a child (cycle)");
            int& p = parent[std::size_t(child)];
            if (p != -1)
                fail("node " + n(child) + " has two parents: node " + n(p) + " and node " + n(i));
            p = int(i);
        }
    }
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
        // With one parent each, a chain longer than the node count must loop.
        std::size_t steps = 0;
        for (int p = parent[i]; p != -1; p = parent[std::size_t(p)])
            if (++steps > m.nodes.size())
                fail("node " + n(i) + " is part of a cycle in the node hierarchy");
    }
    for (std::size_t s = 0; s < m.scenes.size(); ++s)
        for (int root : m.scenes[s].nodes) {
            checkIndex(root, m.nodes.size(), false, "scene " + n(s), "node", "nodes");
            if (parent[std::size_t(root)] != -1)
                fail("scene " + n(s) + " lists node " + n(root) +
                     " as a root, but it is a child of node " + n(parent[std::size_t(root)]));
        }
    if (!m.scenes.empty())
        checkIndex(m.defaultScene, m.scenes.size(), true, "the default scene", "scene", "scenes");
}

/** Skins: joints within the limit, each a node of the file. */
void checkSkins(const tinygltf::Model& m) {
    for (std::size_t i = 0; i < m.skins.size(); ++i) {
        const tinygltf::Skin& skin = m.skins[i];
        const std::string what = "skin " + n(i);
        if (skin.joints.empty())
            fail(what + " has no joints");
        if (skin.joints.size() > core::limits::kMaxJointsPerSkin)
            fail(what + " has " + n(skin.joints.size()) + " joints, over the limit of " +
                 n(core::limits::kMaxJointsPerSkin));
        for (std::size_t j = 0; j < skin.joints.size(); ++j)
            if (skin.joints[j] < 0 || std::size_t(skin.joints[j]) >= m.nodes.size())
                fail(what + ": joint " + n(j) + " references node " + n(skin.joints[j]) +
                     ", file has " + n(m.nodes.size()) + " nodes");
        checkIndex(skin.skeleton, m.nodes.size(), true, what + " skeleton", "node", "nodes");
    }
}

/** Materials of the primitives, textures of the materials, images and samplers of the
 *  textures. */
void checkMaterialReferences(const tinygltf::Model& m) {
    for (std::size_t i = 0; i < m.meshes.size(); ++i)
        for (std::size_t p = 0; p < m.meshes[i].primitives.size(); ++p)
            checkIndex(m.meshes[i].primitives[p].material, m.materials.size(), true,
                       "mesh " + n(i) + " primitive " + n(p), "material", "materials");
    for (std::size_t i = 0; i < m.textures.size(); ++i) {
        const std::string what = "texture " + n(i);
        checkIndex(m.textures[i].source, m.images.size(), true, what, "image", "images");
        checkIndex(m.textures[i].sampler, m.samplers.size(), true, what, "sampler", "samplers");
    }
    for (std::size_t i = 0; i < m.materials.size(); ++i) {
        const tinygltf::Material& mat = m.materials[i];
        const std::string what = "material " + n(i) + " ";
        checkTexture(m, mat.pbrMetallicRoughness.baseColorTexture.index, what + "baseColorTexture");
        checkTexture(m, mat.pbrMetallicRoughness.metallicRoughnessTexture.index,
                     what + "metallicRoughnessTexture");
        checkTexture(m, mat.normalTexture.index, what + "normalTexture");
        checkTexture(m, mat.occlusionTexture.index, what + "occlusionTexture");
        checkTexture(m, mat.emissiveTexture.index, what + "emissiveTexture");
    }
}

/** Animation channels: their samplers, and their target nodes (pointers aside, which
 *  convertAnimation checks). */
void checkChannels(const tinygltf::Model& m) {
    for (std::size_t a = 0; a < m.animations.size(); ++a) {
        const tinygltf::Animation& anim = m.animations[a];
        for (std::size_t c = 0; c < anim.channels.size(); ++c) {
            const std::string what = "animation " + n(a) + " channel " + n(c);
            checkIndex(anim.channels[c].sampler, anim.samplers.size(), false, what, "sampler",
                       "samplers in this animation");
            const std::string& path = anim.channels[c].target_path;
            if (path != kSkippedPointer && path != kMalformedPointer)
                checkIndex(anim.channels[c].target_node, m.nodes.size(), false, what + " target",
                           "node", "nodes");
        }
    }
}

} // namespace

void validateStructure(const tinygltf::Model& m) {
    // A material extension the engine lacks leaves the geometry whole: the file loads without
    // it, with a warning (GltfLoader), even when it is required. What else it lacks refuses.
    for (const std::string& extension : m.extensionsRequired)
        if (!supportedRequiredExtensions().count(extension) && !isMaterialExtension(extension))
            fail("extensionsRequired lists " + extension + ", which this engine does not support");
    checkHierarchy(m);
    checkMaterialReferences(m);
    checkSkins(m);
    checkChannels(m);
}

} // namespace asset::detail
