// GPU timer queries: a pair of GL_TIMESTAMP queries around the timed commands (timestamps also
// behave on llvmpipe, where GL_TIME_ELAPSED around compute-only work misreports), read without
// stalling when possible.
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

} // namespace gl
