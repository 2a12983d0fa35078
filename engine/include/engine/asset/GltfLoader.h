// glTF 2.0 import: the only entry point to tinygltf. Produces an engine-owned scene::Model.
#pragma once

#include "engine/core/Result.h"
#include "engine/scene/Model.h"

#include <filesystem>
#include <set>
#include <span>
#include <string>

namespace asset {

struct LoadOptions {
    /** Decode images into scene::Image pixels. Without it only their headers are checked, so
     *  a file whose image data is corrupt loads: glass-cpu-bench times loading both ways, every
     *  tool decodes. */
    bool decodeImages = true;
};

/** Loads a .gltf (embedded, data-URI or external buffers) or .glb file, chosen by content.
 *
 *  Validates everything the engine later indexes (nodes, meshes, accessors, buffer views,
 *  buffers, materials, textures, skins and their joints, animation targets), the hierarchy (no
 *  cycles, one parent per node), weights (no all-zero or NaN influences), extensionsRequired,
 *  asset.version (2.x) and minVersion (at most 2.0), and the engine's limits (core/Limits.h).
 *  On failure returns an Error naming the function, the file and the element; no partial model
 *  is returned. What the engine can do without is not refused: POINTS and LINES primitives are
 *  left out and extensions the file uses without requiring them are ignored, each with a line
 *  in Model::warnings (also logged). Generates flat normals where NORMAL is missing and
 *  tangents where a normal map needs them. Never throws. */
core::Result<scene::Model> loadGltf(const std::filesystem::path& path,
                                    const LoadOptions& options = {});

/** loadGltf() over bytes already in memory: `file` names them in errors, external buffers and
 *  images resolve against `baseDirectory`. */
core::Result<scene::Model> loadGltfFromMemory(std::span<const std::uint8_t> bytes,
                                              const std::string& file,
                                              const std::filesystem::path& baseDirectory,
                                              const LoadOptions& options = {});

/** Extensions this engine implements: a file may list them in extensionsRequired. A file that
 *  requires another is refused naming it; one that only uses another loads without it, with a
 *  warning (scene::Model::warnings). */
const std::set<std::string>& supportedRequiredExtensions();

} // namespace asset
