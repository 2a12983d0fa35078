// Always-on checks for API misuse and broken invariants. Bad *data* never reaches these: it is
// reported through core::Error instead (see Result.h).
#pragma once

#include <source_location>
#include <string_view>

namespace core {

/** Prints "file:line: function(): check `expr` failed: message" to stderr and aborts. */
[[noreturn]] void checkFailed(std::string_view expression, std::string_view message,
                              std::source_location where = std::source_location::current());

} // namespace core

/** Aborts with file, line and message when `cond` is false; active in every build type. */
#define ENGINE_CHECK(cond, message)                                                                \
    do {                                                                                           \
        if (!(cond)) [[unlikely]]                                                                  \
            ::core::checkFailed(#cond, (message));                                                 \
    } while (false)
