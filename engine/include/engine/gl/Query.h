// GPU timer queries (GL_TIME_ELAPSED), read without stalling when possible.
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
    std::uint32_t mId = 0;
    bool mIssued = false;
};

} // namespace gl
