// Presets: every parameter the viewer's panel shows (the viewer's own settings, each plugin's
// parameters) and the camera, as JSON; also the `--set KEY=VALUE` syntax over all of them.
#pragma once

#include "OrbitCamera.h"
#include "engine/core/Result.h"
#include "engine/plugin/ParameterSet.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace viewer {

inline constexpr const char* kPresetFormat = "glass-viewer-preset/1";

/** One named parameter set: "viewer" or a plugin's name. */
struct Scope {
    std::string name;
    plugin::ParameterSet* parameters = nullptr;
};

/** The viewer's own settings. `clips` and `environments` are the current model's clip names and
 *  the environments found; `methods` are the choices of the split view's second method. */
plugin::ParameterSet viewerParameters(const std::vector<std::string>& clips,
                                      const std::vector<std::string>& environments,
                                      const std::vector<std::string>& methods);

/** Copies every value of `from` whose name `to` also declares and accepts (choices that no
 *  longer exist are left at `to`'s value). */
void copyValues(const plugin::ParameterSet& from, plugin::ParameterSet& to);

nlohmann::json presetJson(const std::vector<Scope>& scopes, const Orbit& orbit);

/** Applies a preset; `source` names it in errors. Every value is checked before any is set: on
 *  an error (unknown scope or key, bad value, wrong format) nothing changes. A scope or key the
 *  preset lacks keeps its value. */
core::Status applyPreset(const nlohmann::json& preset, const std::vector<Scope>& scopes,
                         Orbit& orbit, const std::string& source);

/** Reads and parses a preset file; errors name the file. */
core::Result<nlohmann::json> readPreset(const std::filesystem::path& path);
/** Writes a preset atomically (no partial file on failure). */
core::Status writePreset(const std::filesystem::path& path, const nlohmann::json& preset);

/** "KEY=VALUE" or "SCOPE.KEY=VALUE": an unqualified key is looked up in each scope in order. */
core::Status setAssignment(const std::vector<Scope>& scopes, const std::string& assignment);

} // namespace viewer
