// GL-free enums shared by the GL wrappers and their users (frame graph, renderer).
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
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
    RG32UI,
    RGBA32UI,
    Depth32F,
};

bool isDepth(Format format);
/** An unsigned-integer format: read with texelFetch or as an image, never filtered. */
bool isInteger(Format format);

constexpr std::size_t bytesPerTexel(Format format) {
    switch (format) {
    case Format::RGBA8:
    case Format::SRGB8_A8:
    case Format::R32F:
    case Format::R32UI:
    case Format::Depth32F:
        return 4;
    case Format::RGBA16F:
    case Format::RG32F:
    case Format::RG32UI:
        return 8;
    case Format::RGBA32F:
    case Format::RGBA32UI:
        return 16;
    }
    return 0;
}

/** What a 2D texture is: size, format, mip levels (0 = the full chain). */
struct TextureDesc {
    glm::ivec2 size{1, 1};
    Format format = Format::RGBA8;
    int levels = 1;
    bool operator==(const TextureDesc&) const = default;
    /** GPU memory of the texture's texels, all mip levels (the driver's padding aside). */
    std::size_t bytes() const {
        std::size_t total = 0;
        glm::ivec2 level = size;
        for (int i = 0; i < levels; ++i, level = glm::max(level / 2, glm::ivec2(1)))
            total += std::size_t(level.x) * std::size_t(level.y) * bytesPerTexel(format);
        return total;
    }
};

/** A buffer's size in bytes (the frame graph's transient buffers). */
struct BufferDesc {
    std::size_t size = 0;
    bool operator==(const BufferDesc&) const = default;
    std::size_t bytes() const { return size; }
};

enum class Filter : std::uint8_t { Nearest, Linear, LinearMipmap };
enum class Wrap : std::uint8_t { Repeat, Clamp, MirroredRepeat };

} // namespace gl
