// Always-on checks for API misuse and broken invariants. Bad *data* never reaches these: it is
// reported through core::Error instead (see Result.h).
#pragma once

#include <string_view>

namespace core {

/** Where a check is written (std::source_location is not usable with clang 14 on libstdc++ 12,
 *  which the fuzz build uses; the compilers' builtins behind it are). */
struct SourceLocation {
    const char* file = __builtin_FILE();
    int line = __builtin_LINE();
    const char* function = __builtin_FUNCTION();
};

/** Prints "file:line: function(): check `expr` failed: message" to stderr and aborts. */
[[noreturn]] void checkFailed(std::string_view expression, std::string_view message,
                              SourceLocation where = {});

} // namespace core

/** Aborts with file, line and message when `cond` is false; active in every build type. */
#define ENGINE_CHECK(cond, message)                                                                \
    do {                                                                                           \
        if (!(cond)) [[unlikely]]                                                                  \
            ::core::checkFailed(#cond, (message));                                                 \
    } while (false)
