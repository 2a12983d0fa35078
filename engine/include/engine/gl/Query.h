// GPU timer queries: a pair of GL_TIMESTAMP queries around the timed commands (timestamps also
// behave on llvmpipe, where GL_TIME_ELAPSED around compute-only work misreports), read without
// stalling when possible; fences, asked about without waiting.
#pragma once

#include <cstdint>
#include <optional>

namespace gl {

class TimerQuery {
public:
    TimerQuery();
    ~TimerQuery();
    TimerQuery(TimerQuery&& other) noexcept;
    TimerQuery& operator=(TimerQuery&& other) noexcept;
    TimerQuery(const TimerQuery&) = delete;
    TimerQuery& operator=(const TimerQuery&) = delete;

    void begin();
    void end();
    /** Elapsed GPU nanoseconds once available; `wait` blocks until it is. */
    std::optional<std::uint64_t> resultNs(bool wait) const;

private:
    std::uint32_t mIds[2] = {0, 0};
    bool mIssued = false;
};

/** A point in the GL command stream the CPU can ask about without waiting: whether the GPU has
 *  passed it (everything issued before insert() is done). For reading back a result a later
 *  frame, never stalling this one. */
class Fence {
public:
    Fence() = default;
    ~Fence();
    Fence(Fence&& other) noexcept;
    Fence& operator=(Fence&& other) noexcept;
    Fence(const Fence&) = delete;
    Fence& operator=(const Fence&) = delete;

    /** Places the fence after the commands issued so far (replacing an earlier one). */
    void insert();
    /** Whether inserted and passed (a non-blocking query; it does not flush: the fence passes
     *  once the commands before it have been flushed, at the latest by the frame's end). */
    bool passed() const;
    explicit operator bool() const { return mSync != nullptr; }

private:
    void* mSync = nullptr;
};

} // namespace gl
