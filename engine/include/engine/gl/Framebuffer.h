// RAII GL framebuffer object over textures.
#pragma once

#include "engine/core/Result.h"
#include "engine/gl/Texture.h"

#include <cstdint>
#include <vector>

namespace gl {

class Framebuffer {
public:
    Framebuffer();
    ~Framebuffer();
    Framebuffer(Framebuffer&& other) noexcept;
    Framebuffer& operator=(Framebuffer&& other) noexcept;
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;

    /** Attaches colour textures (in draw-buffer order) and an optional depth texture, then
     *  checks completeness: an incomplete FBO is an Error naming `name` and the status. */
    core::Status attach(const char* name, const std::vector<const Texture*>& colors,
                        const Texture* depth, int level = 0);
    /** Binds for drawing and sets the viewport to the attachments' size. */
    void bind() const;
    /** attach(), then bind() when complete: what a pass does before it draws. The error is
     *  attach()'s, for the pass to return. */
    core::Status bindTargets(const char* name, const std::vector<const Texture*>& colors,
                             const Texture* depth);
    /** Binds the default framebuffer (the window) with the given viewport. */
    static void bindDefault(glm::ivec2 size);
    /** Copies rectangle `source` (x, y, width, height; GL's bottom-up rows) of colour
     *  attachment 0 to rectangle `destination` of the window: unfiltered when the sizes match,
     *  bilinear when scaling. */
    void blitToDefault(glm::ivec4 source, glm::ivec4 destination) const;
    /** Copies the first `size` pixels of `source`'s colour attachment 0 into this framebuffer's
     *  colour attachments, unfiltered, converting between colour formats (no depth). */
    void blitColorFrom(const Framebuffer& source, glm::ivec2 size) const;
    /** The window's back buffer as RGBA8, rows top to bottom (synchronises). */
    static std::vector<std::uint8_t> readDefault(glm::ivec2 size);

    std::uint32_t id() const { return mId; }

private:
    std::uint32_t mId = 0;
    glm::ivec2 mSize{0};
};

} // namespace gl
