// The fuzz targets that wrap their input in a glTF: the GLB of `json` and `bin` loaded as a
// shipped file would be, external references resolving against a folder that does not exist.
// GLASS_FUZZ_VERBOSE=1 prints what the input reached (scripts/fuzz).
#pragma once

#include "engine/asset/Glb.h"
#include "engine/asset/GltfLoader.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>

namespace fuzz {

inline void loadGlb(const std::string& json, std::span<const std::uint8_t> bin, const char* file) {
    const auto model =
        asset::loadGltfFromMemory(asset::encodeGlb(json, bin), file, "/nonexistent-glass-fuzz-dir");
    if (std::getenv("GLASS_FUZZ_VERBOSE"))
        std::fprintf(stderr, "%s\n", model.ok() ? "loaded" : model.error().message.c_str());
}

} // namespace fuzz
