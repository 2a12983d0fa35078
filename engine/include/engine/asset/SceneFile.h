// Scene files: a JSON world of characters (README "Scene files"). Reading loads each model
// once, however many characters place it; writing is atomic.
#pragma once

#include "engine/asset/GltfLoader.h"
#include "engine/core/Result.h"
#include "engine/scene/World.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace asset {

/** Reads a scene file: optional "environment" (an HDR path relative to the file), "ground"
 *  (bool), "camera" ({"position", "target", "yfov"}), and a "characters" array, each with
 *  "model" (a path relative to the file, or builtin:...), "translation" [x, y, z], "rotation"
 *  [x, y, z, w], "scale" [x, y, z], what it plays ("clip" (name or index), "time_offset",
 *  "speed", "loop", or "layers"; "transitions", "root_motion", "morph_weights", "paused_at":
 *  README "Scene files"), "glass" (auto, all, none), "ior", "tint" [r, g, b], "dispersion" and
 *  "name". Keys it does
 *  not know are reported as warnings (core::logWarning), not refused. Fails, naming the file
 *  and the key (`crowd.json: characters[3].clip: "Jump" not in Fox.glb (clips: Survey, Walk,
 *  Run)`), on bad JSON, a wrong type or value, a model that does not load (naming the
 *  character and the path), more than core::limits::kMaxCharacters characters or
 *  kMaxSceneVertices vertices in all. */
core::Result<scene::World> loadScene(const std::filesystem::path& path,
                                     const LoadOptions& options = {});

/** loadScene() of scene file text already in memory: `name` stands for the file in messages and
 *  relative paths resolve against `directory`. */
core::Result<scene::World> parseScene(std::string_view text, const std::filesystem::path& directory,
                                      const std::string& name, const LoadOptions& options = {});

/** The limits a scene file is held to, on any world (models side by side, a viewer's
 *  additions): at most core::limits::kMaxCharacters characters and kMaxSceneVertices vertices
 *  in all (each character counts its model's vertices). The error names `name` and the first
 *  character over the limit. */
core::Status checkWorldLimits(const scene::World& world, const std::string& name);

/** The keys of `character`'s scene file entry that say what it plays ("clip" ... "paused_at"),
 *  as the text of one JSON object. */
std::string encodePerformance(const scene::Character& character);

/** True for a path the tools treat as a scene file rather than a model (a .json file). */
bool isSceneFile(const std::filesystem::path& path);

/** The scene file text of `world`, with model and environment paths written relative to
 *  `sceneDirectory` where they lie below it (as characters name them otherwise). */
std::string encodeScene(const scene::World& world, const std::filesystem::path& sceneDirectory);

/** Writes encodeScene(world) to `path` atomically (no half-written file on failure). */
core::Status saveScene(const std::filesystem::path& path, const scene::World& world);

} // namespace asset
