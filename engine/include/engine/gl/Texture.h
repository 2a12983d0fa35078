// RAII GL 2D texture with immutable storage.
#pragma once

#include "engine/gl/Types.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace gl {

class Texture {
public:
    Texture() = default;
    /** Allocates storage; the size must be within the context's GL_MAX_TEXTURE_SIZE (checked:
     *  use validateSize() first for data from files). */
    explicit Texture(const TextureDesc& desc);
    ~Texture();
    Texture(Texture&& other) noexcept;
    Texture& operator=(Texture&& other) noexcept;
    Texture(const Texture&) = delete;
    Texture& operator=(const Texture&) = delete;

    /** Uploads a whole level: `data` holds rows bottom to top in the texture's format
     *  (RGBA8/SRGB8_A8: 4 bytes per texel; float formats: floats, RGBA16F takes float RGBA). */
    void upload(int level, const void* data);
    void generateMipmaps();
    void setSampling(Filter filter, Wrap wrap);
    /** Reads a level back as RGBA float (colour formats) or depth float (synchronises). */
    std::vector<float> downloadFloat(int level = 0) const;
    /** An unsigned-integer texture's texels as four words each (synchronises). */
    std::vector<std::uint32_t> downloadUint(int level = 0) const;
    /** Reads an 8-bit colour level back as RGBA bytes (synchronises). */
    std::vector<std::uint8_t> downloadRgba8(int level = 0) const;

    std::uint32_t id() const { return mId; }
    const TextureDesc& desc() const { return mDesc; }
    glm::ivec2 size(int level = 0) const;
    int levels() const { return mDesc.levels; }
    explicit operator bool() const { return mId != 0; }

    /** GL_MAX_TEXTURE_SIZE of the current context. */
    static int maxSize();

private:
    std::uint32_t mId = 0;
    TextureDesc mDesc;
};

/** Reverses the row order of RGBA pixels: GL rows run bottom to top, images top to bottom. */
template <class T> std::vector<T> flipRows(std::vector<T> pixels, glm::ivec2 size) {
    const std::size_t row = std::size_t(size.x) * 4u;
    for (int y = 0; y < size.y / 2; ++y)
        std::swap_ranges(pixels.begin() + std::ptrdiff_t(std::size_t(y) * row),
                         pixels.begin() + std::ptrdiff_t(std::size_t(y + 1) * row),
                         pixels.begin() + std::ptrdiff_t(std::size_t(size.y - 1 - y) * row));
    return pixels;
}

} // namespace gl
