// Presets as JSON and --set assignments over the viewer's parameter scopes.
#include "Preset.h"

#include "engine/core/Files.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace viewer {

using Type = plugin::Parameter::Type;

namespace {

/** The scene's: the clip, the clock, the environment, subdivision, exposure and the ground. */
void declareScene(plugin::ParameterSet& p, const std::vector<std::string>& clips,
                  const std::vector<std::string>& environments) {
    const std::vector<std::string> clipChoices =
        clips.empty() ? std::vector<std::string>{"(rest pose)"} : clips;
    p.declare({"clip", "Clip", Type::Enum, 0, 0, 0, clipChoices,
               "the animation clip the selected character plays"});
    p.declare({"playing", "Playing", Type::Bool, 0, 1, 1, {}, "space: play or pause"});
    p.declare({"speed", "Speed", Type::Float, 0.0, 4.0, 1.0, {}, "the scene clock's rate"});
    p.declare({"loop",
               "Loop",
               Type::Bool,
               0,
               1,
               1,
               {},
               "off: the selected character stops at its clip's end"});
    p.declare({"crossfade",
               "Crossfade (s)",
               Type::Float,
               0.0,
               2.0,
               0.3,
               {},
               "a clip change fades from what plays to the new clip over this long, from the "
               "scene time it is made at (saved as a transition); 0 snaps"});
    p.declare({"skeleton",
               "Skeleton",
               Type::Bool,
               0,
               1,
               0,
               {},
               "draws the selected character's joints over the frame"});
    p.declare({"environment", "Environment", Type::Enum, 0, 0, 0, environments,
               "the HDR around the character"});
    p.declare({"env-rotation",
               "Rotation (deg)",
               Type::Float,
               0.0,
               360.0,
               0.0,
               {},
               "environment rotation about the vertical axis"});
    p.declare({"subdiv",
               "Subdivision",
               Type::Int,
               0,
               4,
               0,
               {},
               "OpenSubdiv level of every mesh, refined each frame from the deformed mesh on the "
               "GPU (0: the file's triangles; each level has four times the triangles)"});
    p.declare({"exposure", "Exposure", Type::Float, 0.05, 8.0, 1.0, {}, "before tonemapping"});
    p.declare({"ground", "Ground plane", Type::Bool, 0, 1, 1, {}, "a plane under the character"});
    p.declare({"shadows",
               "Shadows",
               Type::Bool,
               0,
               1,
               1,
               {},
               "the lights cast shadows (each light's own in the Lights section)"});
    p.declare({"shadow-map",
               "Shadow map view",
               Type::Enum,
               0,
               0,
               0,
               {"off", "depth", "glass", "caustics"},
               "a debug view in place of the scene: the lights' shadow atlas, the casters' "
               "depth, the glass's transmittance or the caustics it focuses"});
}

/** The view's: temporal accumulation, the A/B split, the render scale and the timings. */
void declareView(plugin::ParameterSet& p, const std::vector<std::string>& methods) {
    p.declare({"temporal",
               "Accumulate",
               Type::Bool,
               0,
               1,
               0,
               {},
               "temporal accumulation: each frame jittered and blended into the history, each "
               "pixel reprojected by what it shows (T)"});
    p.declare({"history-weight",
               "History weight",
               Type::Float,
               0.0,
               0.99,
               0.7,
               {},
               "the history's weight while anything moves: higher is smoother and lags more"});
    p.declare({"moving-jitter",
               "Jitter while moving",
               Type::Float,
               0.0,
               1.0,
               0.5,
               {},
               "the jitter's extent while anything moves, a share of the pixel (paused: the "
               "whole pixel)"});
    p.declare({"converge-paused",
               "Converge while paused",
               Type::Bool,
               0,
               1,
               1,
               {},
               "while nothing moves, every frame weighs the same: the view converges to the "
               "many-sample image"});
    p.declare({"temporal-view",
               "Temporal view",
               Type::Enum,
               0,
               0,
               0,
               {"off", "rejected history", "motion vectors"},
               "rejected: red where the history was dropped, green where it was clipped; "
               "motion: hue its direction, brightness its length up to 8 pixels"});
    p.declare({"split", "A/B split", Type::Bool, 0, 1, 0, {}, "compare two methods side by side"});
    p.declare({"split-method", "Right side", Type::Enum, 0, 0, 0,
               methods.empty() ? std::vector<std::string>{"(none)"} : methods,
               "the method drawn right of the divider"});
    p.declare({"split-position",
               "Divider",
               Type::Float,
               0.0,
               1.0,
               0.5,
               {},
               "where the divider is, as a fraction of the width"});
    p.declare({"render-scale",
               "Render scale",
               Type::Float,
               0.25,
               1.0,
               1.0,
               {},
               "render the view at this fraction of its size, scaled up to show (speed on CPUs)"});
    p.declare({"exact-timings",
               "Exact pass times",
               Type::Bool,
               0,
               1,
               0,
               {},
               "finish each pass before timing it (true per-pass GPU times, slower frames)"});
}

} // namespace

plugin::ParameterSet viewerParameters(const std::vector<std::string>& clips,
                                      const std::vector<std::string>& environments,
                                      const std::vector<std::string>& methods) {
    plugin::ParameterSet p;
    declareScene(p, clips, environments);
    declareView(p, methods);
    return p;
}

void copyValues(const plugin::ParameterSet& from, plugin::ParameterSet& to) {
    for (const plugin::Parameter& p : to.declarations())
        if (from.find(p.name))
            (void)to.set(p.name, from.text(p.name)); // a vanished choice keeps the default
}

nlohmann::json presetJson(const std::vector<Scope>& scopes, const Orbit& orbit) {
    nlohmann::json preset = {{"format", kPresetFormat}};
    for (const Scope& scope : scopes) {
        nlohmann::json values = nlohmann::json::object();
        for (const plugin::Parameter& p : scope.parameters->declarations())
            values[p.name] = scope.parameters->text(p.name);
        preset["parameters"][scope.name] = values;
    }
    preset["camera"] = {{"target", {orbit.target.x, orbit.target.y, orbit.target.z}},
                        {"distance", orbit.distance},
                        {"azimuth", orbit.azimuth},
                        {"elevation", orbit.elevation}};
    return preset;
}

namespace {

const Scope* findScope(const std::vector<Scope>& scopes, const std::string& name) {
    const auto it =
        std::find_if(scopes.begin(), scopes.end(), [&](const Scope& s) { return s.name == name; });
    return it == scopes.end() ? nullptr : &*it;
}

core::Result<Orbit> orbitFrom(const nlohmann::json& camera, Orbit orbit, const std::string& where) {
    auto number = [&](const nlohmann::json& v, const char* key) -> core::Result<float> {
        if (!v.is_number() || !std::isfinite(v.get<double>()))
            return core::Error{where + ".camera." + key + ": expected a finite number"};
        return v.get<float>();
    };
    if (!camera.is_object())
        return core::Error{where + ".camera: expected an object"};
    for (const auto& [key, value] : camera.items()) {
        if (key == "target") {
            if (!value.is_array() || value.size() != 3)
                return core::Error{where + ".camera.target: expected [x, y, z]"};
            for (int i = 0; i < 3; ++i) {
                auto c = number(value[std::size_t(i)], "target");
                if (!c)
                    return c.error();
                orbit.target[i] = *c;
            }
            continue;
        }
        float* field = key == "distance"    ? &orbit.distance
                       : key == "azimuth"   ? &orbit.azimuth
                       : key == "elevation" ? &orbit.elevation
                                            : nullptr;
        if (!field)
            return core::Error{where + ".camera: unknown key '" + key + "'"};
        auto v = number(value, key.c_str());
        if (!v)
            return v.error();
        *field = *v;
    }
    if (orbit.distance <= 0.0f)
        return core::Error{where + ".camera.distance: must be positive"};
    return orbit;
}

} // namespace

core::Status applyPreset(const nlohmann::json& preset, const std::vector<Scope>& scopes,
                         Orbit& orbit, const std::string& source) {
    if (!preset.is_object() || preset.value("format", "") != kPresetFormat)
        return core::Error{source + R"(: not a glass-viewer preset ("format" must be ")" +
                           kPresetFormat + R"("))"};
    for (const auto& [key, value] : preset.items())
        if (key != "format" && key != "parameters" && key != "camera")
            return core::Error{source + ": unknown key '" + key + "'"};
    // Check everything on copies first, so that a bad preset changes nothing.
    std::vector<plugin::ParameterSet> staged;
    for (const Scope& scope : scopes)
        staged.push_back(*scope.parameters);
    if (preset.contains("parameters")) {
        const nlohmann::json& parameters = preset["parameters"];
        if (!parameters.is_object())
            return core::Error{source + ": \"parameters\" must be an object"};
        for (const auto& [scopeName, values] : parameters.items()) {
            const Scope* scope = findScope(scopes, scopeName);
            if (!scope)
                return core::Error{source + ": parameters." + scopeName +
                                   ": no such parameter set (plugin not loaded?)"};
            if (!values.is_object())
                return core::Error{source + ": parameters." + scopeName + ": expected an object"};
            plugin::ParameterSet& target = staged[std::size_t(scope - scopes.data())];
            for (const auto& [key, value] : values.items()) {
                if (!value.is_string())
                    return core::Error{source + ": parameters." + scopeName + "." + key +
                                       ": expected a string"};
                auto set = target.set(key, value.get<std::string>());
                if (!set)
                    return core::Error{source + ": parameters." + scopeName + "." + key + ": " +
                                       set.error().message};
            }
        }
    }
    Orbit newOrbit = orbit;
    if (preset.contains("camera")) {
        auto parsed = orbitFrom(preset["camera"], orbit, source);
        if (!parsed)
            return parsed.error();
        newOrbit = *parsed;
    }
    for (std::size_t i = 0; i < scopes.size(); ++i)
        *scopes[i].parameters = std::move(staged[i]);
    orbit = newOrbit;
    return {};
}

core::Result<nlohmann::json> readPreset(const std::filesystem::path& path) {
    auto bytes = core::readFile(path, 1u << 20);
    if (!bytes)
        return bytes.error();
    nlohmann::json preset = nlohmann::json::parse(bytes->begin(), bytes->end(), nullptr, false);
    if (preset.is_discarded())
        return core::Error{path.string() + ": not valid JSON"};
    return preset;
}

core::Status writePreset(const std::filesystem::path& path, const nlohmann::json& preset) {
    return core::writeFileAtomic(path, preset.dump(2) + "\n");
}

core::Status setAssignment(const std::vector<Scope>& scopes, const std::string& assignment) {
    const std::size_t equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0)
        return core::Error{"--set '" + assignment + "': expected KEY=VALUE"};
    std::string key = assignment.substr(0, equals);
    const std::string value = assignment.substr(equals + 1);
    const Scope* scope = nullptr;
    if (const std::size_t dot = key.find('.'); dot != std::string::npos) {
        scope = findScope(scopes, key.substr(0, dot));
        if (!scope)
            return core::Error{"--set " + key + ": no parameter set '" + key.substr(0, dot) + "'"};
        key = key.substr(dot + 1);
    } else {
        for (const Scope& s : scopes)
            if (s.parameters->find(key)) {
                scope = &s;
                break;
            }
        if (!scope) {
            std::string known;
            for (const Scope& s : scopes)
                for (const plugin::Parameter& p : s.parameters->declarations())
                    known += (known.empty() ? "" : ", ") + p.name;
            return core::Error{"--set " + key + ": no such parameter (known: " + known + ")"};
        }
    }
    auto set = scope->parameters->set(key, value);
    if (!set)
        return core::Error{"--set " + scope->name + "." + key + ": " + set.error().message};
    return {};
}

} // namespace viewer
