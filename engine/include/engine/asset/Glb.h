// The GLB container (glTF 2.0 binary): a JSON chunk and an optional BIN chunk.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace asset {

/** Packs `json` (padded with spaces) and, when not empty, `bin` (padded with zeros) into a
 *  version-2 GLB file's bytes. */
std::vector<std::uint8_t> encodeGlb(const std::string& json, std::span<const std::uint8_t> bin);

} // namespace asset
