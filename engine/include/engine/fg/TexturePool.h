// Transient texture pool keyed by descriptor: the frame graph acquires and releases textures
// through it, so lifetimes that do not overlap share one GPU texture, and textures survive
// across frames. GPU objects come from an allocator (the renderer's makes gl::Textures).
#pragma once

#include "engine/gl/Types.h"

#include <cstddef>
#include <vector>

namespace fg {

/** Makes and destroys the GPU objects behind pooled textures. */
class TextureAllocator {
public:
    virtual ~TextureAllocator() = default;
    virtual void* allocate(const gl::TextureDesc& desc) = 0;
    virtual void release(void* object) = 0;
};

class TexturePool {
public:
    explicit TexturePool(TextureAllocator& allocator) : mAllocator(allocator) {}
    ~TexturePool();
    TexturePool(const TexturePool&) = delete;
    TexturePool& operator=(const TexturePool&) = delete;

    /** A free texture of exactly `desc`, or a new one. */
    void* acquire(const gl::TextureDesc& desc);
    /** Returns a texture to the free list. */
    void release(void* object);
    /** Call once per frame: textures unused for `maxIdleFrames` frames are destroyed. */
    void endFrame(int maxIdleFrames = 8);

    std::size_t allocatedCount() const { return mEntries.size(); }
    /** Most textures ever allocated at once. */
    std::size_t peakCount() const { return mPeak; }
    std::size_t inUseCount() const;
    /** GPU memory of every pooled texture (gl::TextureDesc::bytes). */
    std::size_t allocatedBytes() const {
        std::size_t total = 0;
        for (const Entry& e : mEntries)
            total += e.desc.bytes();
        return total;
    }

private:
    struct Entry {
        gl::TextureDesc desc;
        void* object = nullptr;
        bool inUse = false;
        int idleFrames = 0;
    };
    TextureAllocator& mAllocator;
    std::vector<Entry> mEntries;
    std::size_t mPeak = 0;
};

} // namespace fg
