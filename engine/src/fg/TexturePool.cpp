// Transient texture pool.
#include "engine/fg/TexturePool.h"

#include "engine/core/Check.h"

#include <algorithm>

namespace fg {

TexturePool::~TexturePool() {
    for (Entry& e : mEntries)
        mAllocator.release(e.object);
}

void* TexturePool::acquire(const gl::TextureDesc& desc) {
    for (Entry& e : mEntries)
        if (!e.inUse && e.desc == desc) {
            e.inUse = true;
            e.idleFrames = 0;
            return e.object;
        }
    Entry entry{desc, mAllocator.allocate(desc), true, 0};
    mEntries.push_back(entry);
    mPeak = std::max(mPeak, mEntries.size());
    return entry.object;
}

void TexturePool::release(void* object) {
    for (Entry& e : mEntries)
        if (e.object == object) {
            ENGINE_CHECK(e.inUse, "TexturePool::release() of a texture not in use");
            e.inUse = false;
            return;
        }
    ENGINE_CHECK(false, "TexturePool::release() of a texture the pool does not own");
}

void TexturePool::endFrame(int maxIdleFrames) {
    for (Entry& e : mEntries)
        if (!e.inUse)
            ++e.idleFrames;
    const auto stale = [&](const Entry& e) { return !e.inUse && e.idleFrames > maxIdleFrames; };
    for (Entry& e : mEntries)
        if (stale(e))
            mAllocator.release(e.object);
    mEntries.erase(std::remove_if(mEntries.begin(), mEntries.end(), stale), mEntries.end());
}

std::size_t TexturePool::inUseCount() const {
    return std::size_t(
        std::count_if(mEntries.begin(), mEntries.end(), [](const Entry& e) { return e.inUse; }));
}

} // namespace fg
