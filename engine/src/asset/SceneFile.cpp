// Scene files: JSON to scene::World (models loaded once each) and back.
#include "engine/asset/SceneFile.h"

#include "engine/asset/HdrImage.h"
#include "engine/asset/ModelLoader.h"
#include "engine/core/Files.h"
#include "engine/core/Limits.h"
#include "engine/core/Log.h"

#include "SceneJson.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string_view>

namespace asset {

using namespace scenefile;

namespace {

std::string fileName(const std::string& path) {
    return path.rfind("builtin:", 0) == 0 ? path : std::filesystem::path(path).filename().string();
}

/** Resolves a model path of the scene file: builtin: names as they are, files relative to it. */
std::string resolve(const std::filesystem::path& directory, const std::string& path) {
    if (path.rfind("builtin:", 0) == 0)
        return path;
    return (directory / path).lexically_normal().string();
}

const char* lightTypeName(scene::Light::Type type) {
    return type == scene::Light::Type::Directional ? "directional"
           : type == scene::Light::Type::Spot      ? "spot"
                                                   : "point";
}

/** A light's "shadow" object: whether it casts, its maps' resolution and its filter's radius. */
scene::LightShadow readShadow(const Json& j, const std::string& key, const std::string& where) {
    if (!j.is_object())
        fail(key, "expected an object, got " + j.dump());
    warnUnknownKeys(j, {"enabled", "resolution", "softness"}, where + key + ".");
    scene::LightShadow shadow;
    if (j.contains("enabled"))
        shadow.enabled = boolean(j["enabled"], key + ".enabled");
    if (j.contains("resolution")) {
        const double r = number(j["resolution"], key + ".resolution");
        if (!(r == std::floor(r) && r >= core::limits::kMinShadowResolution &&
              r <= core::limits::kMaxShadowResolution))
            fail(key + ".resolution", "expected a whole number of texels in " +
                                          std::to_string(core::limits::kMinShadowResolution) +
                                          ".." +
                                          std::to_string(core::limits::kMaxShadowResolution) +
                                          ", got " + j["resolution"].dump());
        shadow.resolution = int(r);
    }
    if (j.contains("softness")) {
        shadow.softness = float(number(j["softness"], key + ".softness"));
        if (!(shadow.softness >= 0.0f && shadow.softness <= 8.0f))
            fail(key + ".softness",
                 "expected a filter radius in 0..8 texels, got " + j["softness"].dump());
    }
    return shadow;
}

/** A light of the scene's "lights" array (README "Scene files"): KHR_lights_punctual's
 *  properties, placed in world space by position and direction. */
scene::PlacedLight readLight(const Json& j, const std::string& key, const std::string& where) {
    if (!j.is_object())
        fail(key, "expected an object, got " + j.dump());
    warnUnknownKeys(j,
                    {"name", "type", "position", "direction", "color", "intensity", "range",
                     "inner_cone_angle", "outer_cone_angle", "shadow"},
                    where + key + ".");
    scene::PlacedLight placed;
    scene::Light& light = placed.light;
    if (!j.contains("type"))
        fail(key + ".type", "missing (directional, point or spot)");
    const std::string type = text(j["type"], key + ".type");
    if (type == "directional")
        light.type = scene::Light::Type::Directional;
    else if (type == "point")
        light.type = scene::Light::Type::Point;
    else if (type == "spot")
        light.type = scene::Light::Type::Spot;
    else
        fail(key + ".type", "expected directional, point or spot, got \"" + type + "\"");
    light.name = j.contains("name") ? text(j["name"], key + ".name") : key;
    if (j.contains("position"))
        placed.position = vector<3>(j["position"], key + ".position");
    else if (light.type != scene::Light::Type::Directional)
        fail(key + ".position", "missing (a " + type + " light's position in the world)");
    if (j.contains("direction")) {
        const glm::vec3 d = vector<3>(j["direction"], key + ".direction");
        if (!(glm::length(d) > 0.0f))
            fail(key + ".direction", "a zero vector points nowhere");
        placed.direction = glm::normalize(d);
    } else if (light.type != scene::Light::Type::Point) {
        fail(key + ".direction", "missing (where the " + type + " light shines)");
    }
    if (j.contains("color")) {
        light.color = vector<3>(j["color"], key + ".color");
        for (int c = 0; c < 3; ++c)
            if (!(light.color[c] >= 0.0f && light.color[c] <= 1.0f))
                fail(key + ".color", "expected linear RGB in [0, 1], got " + j["color"].dump());
    }
    auto nonNegative = [&](const char* name, float& out) {
        if (!j.contains(name))
            return;
        out = float(number(j[name], key + "." + name));
        if (!(out >= 0.0f))
            fail(key + "." + name, "expected a number of at least 0, got " + j[name].dump());
    };
    nonNegative("intensity", light.intensity);
    nonNegative("range", light.range);
    nonNegative("inner_cone_angle", light.innerConeAngle);
    nonNegative("outer_cone_angle", light.outerConeAngle);
    if (light.type == scene::Light::Type::Spot &&
        !(light.innerConeAngle < light.outerConeAngle && light.outerConeAngle <= 1.5708f))
        fail(key, "a spot light needs inner_cone_angle < outer_cone_angle <= pi/2 (radians)");
    if (j.contains("shadow"))
        light.shadow = readShadow(j["shadow"], key + ".shadow", where);
    return placed;
}

/** A character's translation, rotation (a unit quaternion) and scale (none 0). */
void readPlacement(const Json& j, const std::string& key, scene::Character& c) {
    if (j.contains("translation"))
        c.placement.translation = vector<3>(j["translation"], key + ".translation");
    if (j.contains("rotation")) {
        const glm::vec4 q = vector<4>(j["rotation"], key + ".rotation");
        const float length = glm::length(q);
        if (std::abs(length - 1.0f) > 1e-3f)
            fail(key + ".rotation",
                 "expected a unit quaternion [x, y, z, w], its length is " + Json(length).dump());
        c.placement.rotation = glm::normalize(glm::dquat(q.w, q.x, q.y, q.z));
    }
    if (j.contains("scale")) {
        const glm::vec3 scale = vector<3>(j["scale"], key + ".scale");
        c.placement.scale = scale;
        if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f)
            fail(key + ".scale", "a scale of 0 flattens the character");
    }
}

/** A character's glass mode and its overrides of the glass: IOR, tint, dispersion. */
void readGlass(const Json& j, const std::string& key, scene::Character& c) {
    if (j.contains("glass")) {
        const std::string mode = text(j["glass"], key + ".glass");
        if (mode == "auto")
            c.glass = scene::GlassMode::Auto;
        else if (mode == "all")
            c.glass = scene::GlassMode::All;
        else if (mode == "none")
            c.glass = scene::GlassMode::None;
        else
            fail(key + ".glass", "expected auto, all or none, got \"" + mode + "\"");
    }
    if (j.contains("ior")) {
        const double ior = number(j["ior"], key + ".ior");
        if (ior < 1.0 || ior > 4.0)
            fail(key + ".ior", "expected an index of refraction in [1, 4], got " + j["ior"].dump());
        c.overrides.ior = float(ior);
    }
    if (j.contains("tint")) {
        const glm::vec3 tint = vector<3>(j["tint"], key + ".tint");
        if (glm::any(glm::lessThan(tint, glm::vec3(0.0f))) ||
            glm::any(glm::greaterThan(tint, glm::vec3(1.0f))))
            fail(key + ".tint", "expected components in [0, 1], got " + j["tint"].dump());
        c.overrides.tint = tint;
    }
    if (j.contains("dispersion")) {
        const double dispersion = number(j["dispersion"], key + ".dispersion");
        if (dispersion < 0.0 || dispersion > 10.0)
            fail(key + ".dispersion",
                 "expected 20 / Abbe number in [0, 10], got " + j["dispersion"].dump());
        c.overrides.dispersion = float(dispersion);
    }
}

scene::Character readCharacter(const Json& j, const std::string& key, const std::string& where,
                               const std::filesystem::path& directory,
                               std::map<std::string, std::shared_ptr<const scene::Model>>& models,
                               const LoadOptions& options) {
    if (!j.is_object())
        fail(key, "expected an object, got " + j.dump());
    warnUnknownKeys(j,
                    {"name", "model", "translation", "rotation", "scale", "clip", "time_offset",
                     "speed", "loop", "layers", "transitions", "root_motion", "morph_weights",
                     "paused_at", "glass", "ior", "tint", "dispersion", "variant"},
                    where + key + ".");
    scene::Character c;
    if (!j.contains("model"))
        fail(key + ".model", "missing (a model path relative to the scene file)");
    c.modelPath = text(j["model"], key + ".model");
    const std::string resolved = resolve(directory, c.modelPath);
    auto& model = models[resolved];
    if (!model) {
        auto loaded = loadModel(resolved, options);
        if (!loaded)
            fail(key + ".model",
                 "cannot load \"" + c.modelPath + "\" (" + loaded.error().message + ")");
        model = std::make_shared<const scene::Model>(std::move(*loaded));
    }
    c.model = model;
    c.name = j.contains("name") ? text(j["name"], key + ".name") : key;
    readPlacement(j, key, c);
    const scene::Model& m = *c.model;
    c.performance = readPerformance(j, key, m, fileName(c.modelPath));
    if (j.contains("variant")) { // KHR_materials_variants: by name or index
        const Json& variant = j["variant"];
        const std::string wanted =
            variant.is_number_integer() ? variant.dump() : text(variant, key + ".variant");
        const auto found = m.findVariant(wanted);
        if (!found)
            fail(key + ".variant", "\"" + wanted + "\" not in " + fileName(c.modelPath) +
                                       " (variants: " + nameList(m.variants) + ")");
        c.variant = *found;
    }
    readGlass(j, key, c);
    return c;
}

std::size_t vertexCount(const scene::Model& model) {
    std::size_t count = 0;
    for (int node : model.meshNodes())
        for (const scene::Primitive& p :
             model.meshes[std::size_t(model.nodes[std::size_t(node)].mesh)].primitives)
            count += p.vertexCount() * model.nodes[std::size_t(node)].drawCount();
    return count;
}

/** The world of a scene file in `directory`; `where` prefixes warnings (function and file). */
/** camera.through: a character (its index or name) and the node of its file's camera (the
 *  node's index or name), which must hold a perspective camera. */
scene::CameraThrough readThrough(const Json& j, const scene::World& world) {
    const std::string key = "camera.through";
    if (!j.is_object() || !j.contains("character") || !j.contains("node"))
        fail(key, "expected {\"character\": name or index, \"node\": name or index}");
    scene::CameraThrough through;
    const Json& who = j["character"];
    if (who.is_number_unsigned() && who.get<std::size_t>() < world.characters.size()) {
        through.character = who.get<std::size_t>();
    } else {
        const std::string name = who.is_string() ? who.get<std::string>() : who.dump();
        const auto found = std::find_if(world.characters.begin(), world.characters.end(),
                                        [&](const scene::Character& c) { return c.name == name; });
        if (found == world.characters.end())
            fail(key + ".character", "no character " + who.dump() + " in the scene");
        through.character = std::size_t(found - world.characters.begin());
    }
    const scene::Character& c = world.characters[through.character];
    const std::vector<int> cameras = c.model->cameraNodes();
    const Json& node = j["node"];
    for (int n : cameras)
        if ((node.is_number_integer() && node.get<int>() == n) ||
            (node.is_string() && c.model->nodes[std::size_t(n)].name == node.get<std::string>()))
            through.node = n;
    if (through.node < 0)
        fail(key + ".node",
             "no perspective camera on node " + node.dump() + " of " + fileName(c.modelPath));
    return through;
}

scene::World readWorld(const Json& root, const std::filesystem::path& directory,
                       const std::string& where, const LoadOptions& options) {
    if (!root.is_object())
        fail("(root)", "expected an object with a \"characters\" array");
    warnUnknownKeys(root, {"environment", "ground", "camera", "lights", "characters"}, where);
    scene::World world;
    if (root.contains("environment") && !root["environment"].is_null()) {
        // Checked here (readable, an image of an environment's kind and shape), so that every
        // tool refuses the scene alike, naming the key.
        world.environment = resolve(directory, text(root["environment"], "environment"));
        if (auto usable = checkHdr(*world.environment); !usable)
            fail("environment", usable.error().message);
    }
    if (root.contains("ground"))
        world.ground = boolean(root["ground"], "ground");
    if (root.contains("camera")) {
        const Json& cam = root["camera"];
        if (!cam.is_object())
            fail("camera", "expected an object with position, target and yfov");
        warnUnknownKeys(cam, {"position", "target", "yfov", "through"}, where + "camera.");
        scene::WorldCamera camera;
        if (cam.contains("position"))
            camera.position = vector<3>(cam["position"], "camera.position");
        if (cam.contains("target"))
            camera.target = vector<3>(cam["target"], "camera.target");
        if (cam.contains("yfov")) {
            camera.yfov = float(number(cam["yfov"], "camera.yfov"));
            if (camera.yfov <= 0.0f || camera.yfov >= 3.1f)
                fail("camera.yfov", "expected radians in (0, 3.1), got " + cam["yfov"].dump());
        }
        if (glm::length(camera.target - camera.position) <= 0.0f)
            fail("camera", "position and target coincide");
        world.camera = camera;
    }
    if (root.contains("lights")) {
        const Json& lights = root["lights"];
        if (!lights.is_array())
            fail("lights", "expected an array of lights, got " + lights.dump());
        if (lights.size() > core::limits::kMaxLights)
            fail("lights", std::to_string(lights.size()) + " lights, the limit is " +
                               std::to_string(core::limits::kMaxLights));
        for (std::size_t i = 0; i < lights.size(); ++i)
            world.lights.push_back(
                readLight(lights[i], "lights[" + std::to_string(i) + "]", where));
    }
    if (!root.contains("characters") || !root["characters"].is_array())
        fail("characters", "missing (an array of characters)");
    const Json& characters = root["characters"];
    if (characters.size() > core::limits::kMaxCharacters)
        fail("characters", std::to_string(characters.size()) + " characters, the limit is " +
                               std::to_string(core::limits::kMaxCharacters));
    std::map<std::string, std::shared_ptr<const scene::Model>> models;
    std::size_t vertices = 0;
    for (std::size_t i = 0; i < characters.size(); ++i) {
        world.characters.push_back(readCharacter(characters[i],
                                                 "characters[" + std::to_string(i) + "]", where,
                                                 directory, models, options));
        vertices += vertexCount(*world.characters.back().model);
        if (vertices > core::limits::kMaxSceneVertices)
            fail("characters[" + std::to_string(i) + "]",
                 "the scene reaches " + std::to_string(vertices) +
                     " vertices with this character, the limit is " +
                     std::to_string(core::limits::kMaxSceneVertices));
    }
    if (world.camera && root["camera"].contains("through"))
        world.camera->through = readThrough(root["camera"]["through"], world);
    return world;
}

/** nlohmann's DOM parser, told where an error is: its messages give a syntax error's line and
 *  column but not a number's overflow (1e999), and never the key. */
class LocatingParser : public nlohmann::detail::json_sax_dom_parser<Json> {
public:
    LocatingParser(Json& out, std::string_view text)
        : json_sax_dom_parser(out, false), mText(text) {}
    bool key(std::string& name) {
        mKey = name;
        return json_sax_dom_parser::key(name);
    }
    bool parse_error(std::size_t position, const std::string&,
                     const nlohmann::detail::exception& error) {
        const std::string_view before = mText.substr(0, std::min(position, mText.size()));
        const std::size_t line = 1 + std::size_t(std::count(before.begin(), before.end(), '\n'));
        const std::size_t lineStart = before.rfind('\n');
        const std::size_t column =
            lineStart == std::string_view::npos ? before.size() : before.size() - lineStart - 1;
        // What nlohmann says, less its tag and its own position.
        std::string what = error.what();
        if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos)
            what.erase(0, what.find("] ") + 2);
        if (what.rfind("parse error at ", 0) == 0 && what.find(": ") != std::string::npos)
            what.erase(0, what.find(": ") + 2);
        mError = "not valid JSON at line " + std::to_string(line) + ", column " +
                 std::to_string(column) +
                 (mKey.empty() ? std::string() : " (after the key \"" + mKey + "\")") + ": " + what;
        return false;
    }
    const std::string& error() const { return mError; }

private:
    std::string_view mText;
    std::string mKey, mError;
};

core::Status parseJson(std::string_view text, Json& out) {
    LocatingParser parser(out, text);
    try {
        if (Json::sax_parse(text, &parser) && parser.error().empty())
            return {};
    } catch (const std::exception& e) {
        return core::Error{std::string("not valid JSON (") + e.what() + ")"};
    }
    return core::Error{parser.error().empty() ? "not valid JSON" : parser.error()};
}

/** `path` relative to `directory` when it lies below it, else as it is. */
std::string relativeTo(const std::string& path, const std::filesystem::path& directory) {
    if (path.rfind("builtin:", 0) == 0 || directory.empty())
        return path;
    const auto relative = std::filesystem::path(path).lexically_relative(directory);
    if (relative.empty() || *relative.begin() == "..")
        return path;
    return relative.generic_string();
}

} // namespace

core::Status checkWorldLimits(const scene::World& world, const std::string& name) {
    const std::string where = "asset::checkWorldLimits(): " + name + ": ";
    if (world.characters.size() > core::limits::kMaxCharacters)
        return core::Error{where + std::to_string(world.characters.size()) +
                           " characters, the limit is " +
                           std::to_string(core::limits::kMaxCharacters)};
    std::size_t vertices = 0;
    for (std::size_t i = 0; i < world.characters.size(); ++i) {
        vertices += vertexCount(*world.characters[i].model);
        if (vertices > core::limits::kMaxSceneVertices)
            return core::Error{where + "characters[" + std::to_string(i) + "] (" +
                               world.characters[i].name + "): the scene reaches " +
                               std::to_string(vertices) + " vertices with it, the limit is " +
                               std::to_string(core::limits::kMaxSceneVertices)};
    }
    return {};
}

std::string encodePerformance(const scene::Character& character) {
    Json j = Json::object();
    writePerformance(character.performance, *character.model, j);
    return j.dump();
}

bool isSceneFile(const std::filesystem::path& path) {
    return path.extension() == ".json";
}

core::Result<scene::World> loadScene(const std::filesystem::path& path,
                                     const LoadOptions& options) {
    if (!std::filesystem::is_regular_file(path))
        return core::Error{"asset::loadScene(): " + path.string() + ": cannot open the scene file"};
    auto text = core::readFile(path, core::limits::kMaxSceneFileBytes);
    if (!text)
        return core::Error{"asset::loadScene(): " + text.error().message};
    return parseScene(std::string_view(reinterpret_cast<const char*>(text->data()), text->size()),
                      path.parent_path(), path.string(), options);
}

core::Result<scene::World> parseScene(std::string_view text, const std::filesystem::path& directory,
                                      const std::string& name, const LoadOptions& options) {
    const std::string where = "asset::loadScene(): " + name + ": ";
    Json root;
    if (auto parsed = parseJson(text, root); !parsed)
        return core::Error{where + parsed.error().message};
    try {
        scene::World world = readWorld(root, directory, where, options);
        // From here on the paths are the resolved ones (saveScene makes them relative again).
        for (scene::Character& c : world.characters)
            c.modelPath = resolve(directory, c.modelPath);
        return world;
    } catch (const SceneError& e) {
        return core::Error{where + e.message};
    }
}

std::string encodeScene(const scene::World& world, const std::filesystem::path& sceneDirectory) {
    Json root;
    if (world.environment)
        root["environment"] = relativeTo(*world.environment, sceneDirectory);
    root["ground"] = world.ground;
    if (world.camera)
        root["camera"] = {
            {"position",
             {world.camera->position.x, world.camera->position.y, world.camera->position.z}},
            {"target", {world.camera->target.x, world.camera->target.y, world.camera->target.z}},
            {"yfov", world.camera->yfov}};
    if (world.camera && world.camera->through) {
        const scene::CameraThrough& t = *world.camera->through;
        const std::string& node =
            world.characters.at(t.character).model->nodes.at(std::size_t(t.node)).name;
        root["camera"]["through"] = {{"character", t.character},
                                     {"node", node.empty() ? Json(t.node) : Json(node)}};
    }
    for (const scene::PlacedLight& l : world.lights) {
        Json j = {{"name", l.light.name},
                  {"type", lightTypeName(l.light.type)},
                  {"color", {l.light.color.x, l.light.color.y, l.light.color.z}},
                  {"intensity", l.light.intensity}};
        if (l.light.type != scene::Light::Type::Directional)
            j["position"] = {l.position.x, l.position.y, l.position.z};
        if (l.light.type != scene::Light::Type::Point)
            j["direction"] = {l.direction.x, l.direction.y, l.direction.z};
        if (l.light.range > 0.0f)
            j["range"] = l.light.range;
        if (l.light.type == scene::Light::Type::Spot) {
            j["inner_cone_angle"] = l.light.innerConeAngle;
            j["outer_cone_angle"] = l.light.outerConeAngle;
        }
        if (l.light.shadow != scene::LightShadow{})
            j["shadow"] = {{"enabled", l.light.shadow.enabled},
                           {"resolution", l.light.shadow.resolution},
                           {"softness", l.light.shadow.softness}};
        root["lights"].push_back(j);
    }
    root["characters"] = Json::array();
    for (const scene::Character& c : world.characters) {
        Json j;
        j["name"] = c.name;
        j["model"] = relativeTo(c.modelPath, sceneDirectory);
        const scene::Trs& t = c.placement;
        j["translation"] = {t.translation.x, t.translation.y, t.translation.z};
        j["rotation"] = {t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w};
        j["scale"] = {t.scale.x, t.scale.y, t.scale.z};
        writePerformance(c.performance, *c.model, j);
        if (c.variant >= 0 && std::size_t(c.variant) < c.model->variants.size())
            j["variant"] = c.model->variants[std::size_t(c.variant)];
        j["glass"] = c.glass == scene::GlassMode::All    ? "all"
                     : c.glass == scene::GlassMode::None ? "none"
                                                         : "auto";
        if (c.overrides.ior)
            j["ior"] = *c.overrides.ior;
        if (c.overrides.tint)
            j["tint"] = {c.overrides.tint->x, c.overrides.tint->y, c.overrides.tint->z};
        if (c.overrides.dispersion)
            j["dispersion"] = *c.overrides.dispersion;
        root["characters"].push_back(std::move(j));
    }
    return root.dump(2) + "\n";
}

core::Status saveScene(const std::filesystem::path& path, const scene::World& world) {
    auto written = core::writeFileAtomic(path, encodeScene(world, path.parent_path()));
    if (!written)
        return core::Error{"asset::saveScene(): " + written.error().message};
    return {};
}

} // namespace asset
