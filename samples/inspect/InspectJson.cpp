// Model summary as JSON.
#include "InspectJson.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace inspect {

namespace {

/** Each clip: its channels, their interpolations and paths, its duration, and its
 *  KHR_animation_pointer channels, each played or skipped. */
nlohmann::ordered_json describeClips(const scene::Model& model) {
    nlohmann::ordered_json clips = nlohmann::ordered_json::array();
    for (const scene::Animation& a : model.animations) {
        std::set<std::string> modes, paths;
        for (const scene::AnimationChannel& c : a.channels) {
            modes.insert(toString(a.samplers[std::size_t(c.sampler)].interpolation));
            paths.insert(toString(c.path));
        }
        nlohmann::ordered_json pointers = nlohmann::ordered_json::array();
        for (const scene::PointerChannel& p : a.pointers)
            pointers.push_back(
                {{"channel", p.channel}, {"pointer", p.pointer}, {"played", p.played}});
        clips.push_back({{"name", a.name},
                         {"channels", a.channels.size()},
                         {"interpolation", std::vector<std::string>(modes.begin(), modes.end())},
                         {"paths", std::vector<std::string>(paths.begin(), paths.end())},
                         {"duration_s", a.duration},
                         {"pointer_channels", std::move(pointers)}});
    }
    return clips;
}

/** Each transmissive material's glass: transmission, IOR, dispersion, volume, attenuation. */
nlohmann::ordered_json describeGlass(const scene::Model& model) {
    nlohmann::ordered_json glass = nlohmann::ordered_json::array();
    for (const scene::Material& m : model.materials) {
        if (!m.isTransmissive())
            continue;
        nlohmann::ordered_json g;
        g["material"] = m.name;
        g["transmission"] = m.transmissionFactor;
        g["ior"] = m.ior;
        g["ior_from_extension"] = m.hasIor;
        g["dispersion"] = m.dispersion;
        g["roughness"] = m.roughnessFactor;
        g["metallic"] = m.metallicFactor;
        g["volume"] = m.hasVolume;
        g["thickness"] = m.thicknessFactor;
        g["attenuationDistance"] = std::isinf(m.attenuationDistance)
                                       ? nlohmann::ordered_json(nullptr)
                                       : nlohmann::ordered_json(m.attenuationDistance);
        g["attenuationColor"] = {m.attenuationColor.r, m.attenuationColor.g, m.attenuationColor.b};
        g["doubleSided"] = m.doubleSided;
        glass.push_back(g);
    }
    return glass;
}

} // namespace

nlohmann::ordered_json describe(const scene::Model& model) {
    nlohmann::ordered_json j;
    std::size_t primitives = 0, triangles = 0, vertices = 0, maxTargets = 0;
    int maxInfluences = 0;
    nlohmann::ordered_json meshes = nlohmann::ordered_json::array();
    for (const scene::Mesh& mesh : model.meshes) {
        nlohmann::ordered_json m;
        m["name"] = mesh.name;
        nlohmann::ordered_json prims = nlohmann::ordered_json::array();
        for (const scene::Primitive& p : mesh.primitives) {
            ++primitives;
            triangles += p.triangleCount();
            vertices += p.sourceVertexCount;
            maxTargets = std::max(maxTargets, p.targets.size());
            maxInfluences = std::max(maxInfluences, 4 * p.influenceSets());
            prims.push_back({{"vertices", p.sourceVertexCount},
                             {"triangles", p.triangleCount()},
                             {"material", p.material},
                             {"morph_targets", p.targets.size()},
                             {"influences", 4 * p.influenceSets()},
                             {"generated_normals", p.flatNormals},
                             {"generated_tangents", p.generatedTangents}});
        }
        m["primitives"] = prims;
        m["morph_targets"] = mesh.morphTargetCount();
        m["target_names"] = mesh.targetNames;
        meshes.push_back(m);
    }
    j["meshes"] = model.meshes.size();
    j["primitives"] = primitives;
    j["triangles"] = triangles;
    j["vertices"] = vertices;
    j["nodes"] = model.nodes.size();
    j["skins"] = model.skins.size();
    nlohmann::ordered_json joints = nlohmann::ordered_json::array();
    for (const scene::Skin& skin : model.skins)
        joints.push_back(skin.joints.size());
    j["joints_per_skin"] = joints;
    j["max_influences"] = maxInfluences;
    j["max_morph_targets"] = maxTargets;
    j["animations"] = model.animations.size();
    j["animation_list"] = describeClips(model);
    j["variants"] = model.variants; // KHR_materials_variants' names
    j["cameras"] = model.cameras.size();
    nlohmann::ordered_json lights = nlohmann::ordered_json::array();
    for (const scene::Light& l : model.lights) // KHR_lights_punctual
        lights.push_back({{"name", l.name},
                          {"type", l.type == scene::Light::Type::Directional ? "directional"
                                   : l.type == scene::Light::Type::Spot      ? "spot"
                                                                             : "point"},
                          {"intensity", l.intensity}});
    j["lights"] = lights;
    j["materials"] = model.materials.size();
    // The layers glTF's material extensions put on the materials, and how many use each.
    nlohmann::ordered_json layers = nlohmann::ordered_json::object();
    auto count = [&](const char* name, bool (*has)(const scene::Material&)) {
        const auto n = std::count_if(model.materials.begin(), model.materials.end(), has);
        if (n > 0)
            layers[name] = n;
    };
    count("KHR_materials_specular", [](const scene::Material& m) { return m.hasSpecular; });
    count("KHR_materials_clearcoat", [](const scene::Material& m) { return m.hasClearcoat; });
    count("KHR_materials_sheen", [](const scene::Material& m) { return m.hasSheen; });
    count("KHR_materials_iridescence", [](const scene::Material& m) { return m.hasIridescence; });
    count("KHR_materials_anisotropy", [](const scene::Material& m) { return m.hasAnisotropy; });
    j["material_layers"] = layers;
    j["transmissive_materials"] = describeGlass(model);
    j["mesh_list"] = meshes;
    j["warnings"] = model.warnings;
    return j;
}

} // namespace inspect
