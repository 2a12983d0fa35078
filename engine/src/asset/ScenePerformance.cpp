// A character's performance in a scene file: clip layers, transitions, root motion, morph
// weights and a held time, read with errors that name the key, and written back.
#include "SceneJson.h"

#include <algorithm>
#include <charconv>

namespace asset::scenefile {
namespace {

constexpr const char* kShortForm[] = {"clip", "time_offset", "speed", "loop"};

/** A clip by name or index, refused naming the model's clips. */
int readClip(const Json& j, const std::string& key, const scene::Model& model,
             const std::string& modelFile) {
    const std::string wanted = j.is_number_integer() ? j.dump() : text(j, key);
    const auto found = model.findAnimation(wanted);
    if (!found)
        fail(key, (j.is_number_integer() ? "clip " + wanted : "\"" + wanted + "\"") + " not in " +
                      modelFile + " (clips: " + clipList(model) + ")");
    return *found;
}

/** true: repeat, false: clamp, "repeat", "clamp", "ping_pong", or a count of repeats. */
void readLoop(const Json& j, const std::string& key, scene::Layer& layer) {
    layer.repetitions = 0;
    if (j.is_boolean()) {
        layer.loop = j.get<bool>() ? scene::Loop::Repeat : scene::Loop::Clamp;
    } else if (j.is_number_integer()) {
        const long long count = j.get<long long>();
        if (count < 1 || count > 1000000)
            fail(key, "expected a count of repeats in [1, 1000000], got " + j.dump());
        layer.loop = scene::Loop::Repeat;
        layer.repetitions = int(count);
    } else {
        const std::string mode = j.is_string() ? j.get<std::string>() : std::string();
        if (mode == "repeat")
            layer.loop = scene::Loop::Repeat;
        else if (mode == "clamp")
            layer.loop = scene::Loop::Clamp;
        else if (mode == "ping_pong")
            layer.loop = scene::Loop::PingPong;
        else
            fail(key, "expected true, false, \"repeat\", \"clamp\", \"ping_pong\" or a count of "
                      "repeats, got " +
                          j.dump());
    }
}

Json writeLoop(const scene::Layer& layer) {
    switch (layer.loop) {
    case scene::Loop::Clamp:
        return false;
    case scene::Loop::PingPong:
        return "ping_pong";
    case scene::Loop::Repeat:
        break;
    }
    return layer.repetitions > 0 ? Json(layer.repetitions) : Json(true);
}

/** `name` among `names`, else a decimal index below names.size(); -1 when neither. */
int findName(const std::string& name, std::size_t count,
             const std::function<const std::string&(std::size_t)>& nameOf) {
    for (std::size_t i = 0; i < count; ++i)
        if (nameOf(i) == name)
            return int(i);
    int index = -1;
    const auto [end, error] = std::from_chars(name.data(), name.data() + name.size(), index);
    return error == std::errc() && end == name.data() + name.size() && index >= 0 &&
                   std::size_t(index) < count
               ? index
               : -1;
}

/** A joint name or index (its subtree at weight 1), or {"joint": weight, ...}. */
std::vector<scene::MaskEntry> readMask(const Json& j, const std::string& key,
                                       const scene::Model& model, const std::string& modelFile) {
    const auto node = [&](const std::string& name, const std::string& at) {
        const int found =
            findName(name, model.nodes.size(),
                     [&](std::size_t i) -> const std::string& { return model.nodes[i].name; });
        if (found < 0)
            fail(at, "no node \"" + name + "\" in " + modelFile);
        return found;
    };
    std::vector<scene::MaskEntry> mask;
    if (j.is_string() || j.is_number_integer()) {
        mask.push_back({node(j.is_string() ? j.get<std::string>() : j.dump(), key), 1.0});
    } else if (j.is_object() && !j.empty()) {
        for (const auto& [name, weight] : j.items()) {
            const double w = number(weight, key + "." + name);
            if (w < 0.0 || w > 1.0)
                fail(key + "." + name, "expected a weight in [0, 1], got " + weight.dump());
            mask.push_back({node(name, key + "." + name), w});
        }
    } else {
        fail(key, "expected a joint's name or index, or {\"joint\": weight, ...}, got " + j.dump());
    }
    return mask;
}

/** The mask as written: each node by name when it has a unique one, else by index. */
Json writeMask(const std::vector<scene::MaskEntry>& mask, const scene::Model& model) {
    Json j = Json::object();
    for (const scene::MaskEntry& e : mask) {
        const std::string& name = model.nodes[std::size_t(e.node)].name;
        const bool unique = !name.empty() && findName(name, model.nodes.size(),
                                                      [&](std::size_t i) -> const std::string& {
                                                          return model.nodes[i].name;
                                                      }) == e.node;
        j[unique ? name : std::to_string(e.node)] = e.weight;
    }
    return j;
}

/** The short form's or a layer's timing keys. */
void readTiming(const Json& j, const std::string& key, scene::Layer& layer) {
    if (j.contains("time_offset"))
        layer.timeOffset = number(j["time_offset"], key + "time_offset");
    if (j.contains("speed"))
        layer.speed = number(j["speed"], key + "speed");
    if (j.contains("loop"))
        readLoop(j["loop"], key + "loop", layer);
}

scene::Layer readLayer(const Json& j, const std::string& key, const scene::Model& model,
                       const std::string& modelFile) {
    if (!j.is_object())
        fail(key, "expected an object, got " + j.dump());
    warnUnknownKeys(j, {"clip", "weight", "time_offset", "speed", "loop", "additive", "mask"},
                    key + ".");
    if (!j.contains("clip"))
        fail(key + ".clip", "missing (a clip's name or index)");
    scene::Layer layer;
    layer.clip = readClip(j["clip"], key + ".clip", model, modelFile);
    if (j.contains("weight")) {
        layer.weight = number(j["weight"], key + ".weight");
        if (layer.weight < 0.0 || layer.weight > 1000.0)
            fail(key + ".weight", "expected a weight in [0, 1000], got " + j["weight"].dump());
    }
    readTiming(j, key + ".", layer);
    if (j.contains("additive"))
        layer.additive = boolean(j["additive"], key + ".additive");
    if (j.contains("mask"))
        layer.mask = readMask(j["mask"], key + ".mask", model, modelFile);
    return layer;
}

scene::Transition readTransition(const Json& j, const std::string& key, const scene::Model& model,
                                 const std::string& modelFile) {
    if (!j.is_object())
        fail(key, "expected an object, got " + j.dump());
    warnUnknownKeys(j, {"at", "to", "duration"}, key + ".");
    for (const char* required : {"at", "to"})
        if (!j.contains(required))
            fail(key + "." + required, "missing");
    scene::Transition t;
    t.at = number(j["at"], key + ".at");
    t.to = readClip(j["to"], key + ".to", model, modelFile);
    if (j.contains("duration")) {
        t.duration = number(j["duration"], key + ".duration");
        if (t.duration < 0.0)
            fail(key + ".duration", "expected seconds >= 0, got " + j["duration"].dump());
    }
    return t;
}

/** {"target name or index": weight, or {"add": weight}}: by name on every mesh that names the
 *  target, by index on every morphing mesh. */
std::vector<scene::MorphSetting> readMorphWeights(const Json& j, const std::string& key,
                                                  const scene::Model& model,
                                                  const std::string& modelFile) {
    if (!j.is_object())
        fail(key, "expected {\"target name or index\": weight, ...}, got " + j.dump());
    std::vector<scene::MorphSetting> settings;
    for (const auto& [name, value] : j.items()) {
        const std::string at = key + "." + name;
        scene::MorphSetting setting;
        if (value.is_object()) {
            if (value.size() != 1 || !value.contains("add"))
                fail(at, "expected a weight or {\"add\": weight}, got " + value.dump());
            setting.add = true;
            setting.value = number(value["add"], at + ".add");
        } else {
            setting.value = number(value, at);
        }
        std::size_t found = 0, most = 0;
        std::vector<std::string> names;
        for (std::size_t m = 0; m < model.meshes.size(); ++m) {
            const scene::Mesh& mesh = model.meshes[m];
            most = std::max(most, mesh.morphTargetCount());
            for (std::size_t t = 0; t < mesh.targetNames.size(); ++t) {
                names.push_back(mesh.targetNames[t]);
                if (mesh.targetNames[t] == name) {
                    setting.mesh = int(m);
                    setting.target = int(t);
                    settings.push_back(setting);
                    ++found;
                }
            }
        }
        if (found > 0)
            continue;
        int index = -1;
        const auto [end, error] = std::from_chars(name.data(), name.data() + name.size(), index);
        if (error != std::errc() || end != name.data() + name.size() || index < 0 ||
            std::size_t(index) >= most)
            fail(at, "no morph target \"" + name + "\" in " + modelFile + " (targets: " +
                         nameList(names) + "; " + std::to_string(most) + " at most on a mesh)");
        setting.mesh = -1;
        setting.target = index;
        settings.push_back(setting);
    }
    return settings;
}

Json writeMorphWeights(const std::vector<scene::MorphSetting>& settings,
                       const scene::Model& model) {
    Json j = Json::object();
    for (const scene::MorphSetting& s : settings) {
        std::string name = std::to_string(s.target);
        if (s.mesh >= 0) {
            const auto& names = model.meshes[std::size_t(s.mesh)].targetNames;
            if (std::size_t(s.target) < names.size() && !names[std::size_t(s.target)].empty())
                name = names[std::size_t(s.target)];
        }
        j[name] = s.add ? Json{{"add", s.value}} : Json(s.value);
    }
    return j;
}

bool isShortForm(const scene::Performance& p) {
    if (p.layers.size() != 1)
        return p.layers.empty();
    const scene::Layer& l = p.layers.front();
    return l.weight == 1.0 && !l.additive && l.mask.empty();
}

} // namespace

scene::Performance readPerformance(const Json& j, const std::string& key, const scene::Model& model,
                                   const std::string& modelFile) {
    scene::Performance p;
    if (j.contains("layers")) {
        for (const char* shortKey : kShortForm)
            if (j.contains(shortKey))
                fail(key + "." + shortKey,
                     "give the clip and its timing in \"layers\" or as the short form, not both");
        const Json& layers = j["layers"];
        if (!layers.is_array())
            fail(key + ".layers", "expected an array of layers, got " + layers.dump());
        for (std::size_t i = 0; i < layers.size(); ++i)
            p.layers.push_back(
                readLayer(layers[i], key + ".layers[" + std::to_string(i) + "]", model, modelFile));
    } else {
        scene::Layer layer;
        layer.clip = model.animations.empty() ? -1 : 0;
        if (j.contains("clip"))
            layer.clip = readClip(j["clip"], key + ".clip", model, modelFile);
        readTiming(j, key + ".", layer);
        p.layers.push_back(layer);
    }
    if (j.contains("transitions")) {
        const Json& transitions = j["transitions"];
        if (!transitions.is_array())
            fail(key + ".transitions", "expected an array, got " + transitions.dump());
        for (std::size_t i = 0; i < transitions.size(); ++i)
            p.transitions.push_back(readTransition(
                transitions[i], key + ".transitions[" + std::to_string(i) + "]", model, modelFile));
        std::stable_sort(p.transitions.begin(), p.transitions.end(),
                         [](const auto& a, const auto& b) { return a.at < b.at; });
    }
    if (j.contains("root_motion")) {
        const std::string mode = text(j["root_motion"], key + ".root_motion");
        if (mode == "baked")
            p.rootMotion = scene::RootMotion::Baked;
        else if (mode == "in_place")
            p.rootMotion = scene::RootMotion::InPlace;
        else if (mode == "accumulate")
            p.rootMotion = scene::RootMotion::Accumulate;
        else
            fail(key + ".root_motion",
                 "expected \"baked\", \"in_place\" or \"accumulate\", got \"" + mode + "\"");
    }
    if (j.contains("morph_weights"))
        p.morphs = readMorphWeights(j["morph_weights"], key + ".morph_weights", model, modelFile);
    if (j.contains("paused_at"))
        p.pausedAt = number(j["paused_at"], key + ".paused_at");
    return p;
}

void writePerformance(const scene::Performance& p, const scene::Model& model, Json& j) {
    const auto clip = [&](int index) -> Json {
        if (index < 0 || index >= int(model.animations.size()))
            return index;
        const std::string& name = model.animations[std::size_t(index)].name;
        return name.empty() ? Json(index) : Json(name);
    };
    if (isShortForm(p)) {
        if (!p.layers.empty()) {
            const scene::Layer& l = p.layers.front();
            if (l.clip >= 0)
                j["clip"] = clip(l.clip);
            j["time_offset"] = l.timeOffset;
            j["speed"] = l.speed;
            j["loop"] = writeLoop(l);
        }
    } else {
        j["layers"] = Json::array();
        for (const scene::Layer& l : p.layers) {
            Json layer = {{"clip", clip(l.clip)},        {"weight", l.weight},
                          {"time_offset", l.timeOffset}, {"speed", l.speed},
                          {"loop", writeLoop(l)},        {"additive", l.additive}};
            if (!l.mask.empty())
                layer["mask"] = writeMask(l.mask, model);
            j["layers"].push_back(std::move(layer));
        }
    }
    for (const scene::Transition& t : p.transitions)
        j["transitions"].push_back({{"at", t.at}, {"to", clip(t.to)}, {"duration", t.duration}});
    if (p.rootMotion != scene::RootMotion::Baked)
        j["root_motion"] = scene::toString(p.rootMotion);
    if (!p.morphs.empty())
        j["morph_weights"] = writeMorphWeights(p.morphs, model);
    if (p.pausedAt)
        j["paused_at"] = *p.pausedAt;
}

} // namespace asset::scenefile
