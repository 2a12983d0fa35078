// Private to the asset module: reading the GLB container (glTF 2.0 binary), whose checks tinygltf
// leaves out or reports vaguely. engine/asset/Glb.h writes it.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace asset::detail {

/** Version 2, declared length equal to the file size, every chunk inside the file, JSON first,
 *  BIN second (glTF 2.0 section 4.4); throws LoadError naming what is wrong. */
void checkGlbContainer(std::span<const std::uint8_t> bytes);

/** The JSON chunk and the BIN chunk (empty when there is none) of bytes checkGlbContainer
 *  accepted. */
struct GlbChunks {
    std::string_view json;
    std::span<const std::uint8_t> bin;
};
GlbChunks glbChunks(std::span<const std::uint8_t> bytes);

} // namespace asset::detail
