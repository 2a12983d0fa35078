// Transient resource pools.
#include "engine/fg/Pool.h"

#include "engine/core/Check.h"

#include <algorithm>

namespace fg {

template <class Desc> Pool<Desc>::~Pool() {
    for (Entry& e : mEntries)
        mAllocator.release(e.object);
}

template <class Desc> void* Pool<Desc>::acquire(const Desc& desc) {
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

template <class Desc> void Pool<Desc>::release(void* object) {
    for (Entry& e : mEntries)
        if (e.object == object) {
            ENGINE_CHECK(e.inUse, "fg::Pool::release() of an object not in use");
            e.inUse = false;
            return;
        }
    ENGINE_CHECK(false, "fg::Pool::release() of an object the pool does not own");
}

template <class Desc> void Pool<Desc>::endFrame(int maxIdleFrames) {
    for (Entry& e : mEntries)
        if (!e.inUse)
            ++e.idleFrames;
    const auto stale = [&](const Entry& e) { return !e.inUse && e.idleFrames > maxIdleFrames; };
    for (Entry& e : mEntries)
        if (stale(e))
            mAllocator.release(e.object);
    mEntries.erase(std::remove_if(mEntries.begin(), mEntries.end(), stale), mEntries.end());
}

template <class Desc> std::size_t Pool<Desc>::inUseCount() const {
    return std::size_t(
        std::count_if(mEntries.begin(), mEntries.end(), [](const Entry& e) { return e.inUse; }));
}

template class Pool<gl::TextureDesc>;
template class Pool<gl::BufferDesc>;

} // namespace fg
