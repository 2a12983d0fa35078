// The scene file's JSON readers, shared by its parts (the world, a character's performance):
// each fails with the key it read, which loadScene prefixes with the file's name.
#pragma once

#include "engine/core/Log.h"
#include "engine/scene/Model.h"
#include "engine/scene/Performance.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

namespace asset::scenefile {

using Json = nlohmann::json;

/** A scene file error at a key: carries "key: message" up to loadScene, which names the file. */
struct SceneError {
    std::string message;
};

[[noreturn]] inline void fail(const std::string& key, const std::string& message) {
    throw SceneError{key + ": " + message};
}

inline double number(const Json& j, const std::string& key) {
    if (!j.is_number())
        fail(key, "expected a number, got " + j.dump());
    const double value = j.get<double>();
    if (!std::isfinite(value))
        fail(key, "expected a finite number");
    return value;
}

template <int N> glm::vec<N, float> vector(const Json& j, const std::string& key) {
    if (!j.is_array() || j.size() != std::size_t(N))
        fail(key, "expected an array of " + std::to_string(N) + " numbers, got " + j.dump());
    glm::vec<N, float> v;
    for (int i = 0; i < N; ++i)
        v[i] = float(number(j[std::size_t(i)], key + "[" + std::to_string(i) + "]"));
    return v;
}

inline bool boolean(const Json& j, const std::string& key) {
    if (!j.is_boolean())
        fail(key, "expected true or false, got " + j.dump());
    return j.get<bool>();
}

inline std::string text(const Json& j, const std::string& key) {
    if (!j.is_string())
        fail(key, "expected a string, got " + j.dump());
    return j.get<std::string>();
}

inline void warnUnknownKeys(const Json& object, std::initializer_list<const char*> known,
                            const std::string& where) {
    for (const auto& [key, value] : object.items()) {
        bool found = false;
        for (const char* k : known)
            found = found || key == k;
        if (!found)
            core::logWarning(where + key + ": not a key of scene files, ignored");
    }
}

/** `names` for an error, each unnamed one by its index ("none" for no names). */
inline std::string nameList(const std::vector<std::string>& names) {
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i)
        list += (list.empty() ? "" : ", ") + (names[i].empty() ? std::to_string(i) : names[i]);
    return list.empty() ? "none" : list;
}

inline std::string clipList(const scene::Model& model) {
    std::vector<std::string> names;
    for (const scene::Animation& a : model.animations)
        names.push_back(a.name);
    return nameList(names);
}

/** A character's performance from its keys: "clip", "time_offset", "speed" and "loop" (the
 *  one-layer short form) or "layers"; "transitions", "root_motion", "morph_weights" and
 *  "paused_at". `key` names the character, `modelFile` its model in messages. */
scene::Performance readPerformance(const Json& character, const std::string& key,
                                   const scene::Model& model, const std::string& modelFile);

/** The keys readPerformance() reads back to `performance`, written into `character`: the short
 *  form when one plain layer plays. */
void writePerformance(const scene::Performance& performance, const scene::Model& model,
                      Json& character);

} // namespace asset::scenefile
