// Transient resource pools keyed by descriptor: the frame graph acquires and releases textures
// and buffers through them, so lifetimes that do not overlap share one GPU object, and objects
// survive across frames. GPU objects come from an allocator (the renderer's makes gl::Textures
// and gl::Buffers).
#pragma once

#include "engine/gl/Types.h"

#include <cstddef>
#include <vector>

namespace fg {

/** Makes and destroys the GPU objects behind pooled resources of descriptor `Desc`. */
template <class Desc> class Allocator {
public:
    virtual ~Allocator() = default;
    virtual void* allocate(const Desc& desc) = 0;
    virtual void release(void* object) = 0;
};

template <class Desc> class Pool {
public:
    explicit Pool(Allocator<Desc>& allocator) : mAllocator(allocator) {}
    ~Pool();
    Pool(const Pool&) = delete;
    Pool& operator=(const Pool&) = delete;

    /** A free object of exactly `desc`, or a new one. */
    void* acquire(const Desc& desc);
    /** Returns an object to the free list. */
    void release(void* object);
    /** Call once per frame: objects unused for `maxIdleFrames` frames are destroyed. */
    void endFrame(int maxIdleFrames = 8);

    std::size_t allocatedCount() const { return mEntries.size(); }
    /** Most objects ever allocated at once. */
    std::size_t peakCount() const { return mPeak; }
    std::size_t inUseCount() const;
    /** GPU memory of every pooled object (Desc::bytes). */
    std::size_t allocatedBytes() const {
        std::size_t total = 0;
        for (const Entry& e : mEntries)
            total += e.desc.bytes();
        return total;
    }

private:
    struct Entry {
        Desc desc;
        void* object = nullptr;
        bool inUse = false;
        int idleFrames = 0;
    };
    Allocator<Desc>& mAllocator;
    std::vector<Entry> mEntries;
    std::size_t mPeak = 0;
};

using TextureAllocator = Allocator<gl::TextureDesc>;
using TexturePool = Pool<gl::TextureDesc>;
using BufferAllocator = Allocator<gl::BufferDesc>;
using BufferPool = Pool<gl::BufferDesc>;

extern template class Pool<gl::TextureDesc>;
extern template class Pool<gl::BufferDesc>;

} // namespace fg
