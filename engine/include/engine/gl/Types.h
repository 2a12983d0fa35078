// GL-free enums shared by the GL wrappers and their users (frame graph, renderer).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

namespace gl {

enum class Format : std::uint8_t {
    RGBA8,    ///< linear 8-bit
    SRGB8_A8, ///< sRGB-encoded 8-bit
    RGBA16F,
    RGBA32F,
    R32F,
    RG32F,
    R32UI,
    Depth32F,
};

bool isDepth(Format format);

/** What a 2D texture is: size, format, mip levels (0 = the full chain). */
struct TextureDesc {
    glm::ivec2 size{1, 1};
    Format format = Format::RGBA8;
    int levels = 1;
    bool operator==(const TextureDesc&) const = default;
};

enum class Filter : std::uint8_t { Nearest, Linear, LinearMipmap };
enum class Wrap : std::uint8_t { Repeat, Clamp, MirroredRepeat };

} // namespace gl
