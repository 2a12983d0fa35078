// Failure path of ENGINE_CHECK.
#include "engine/core/Check.h"

#include <cstdio>
#include <cstdlib>

namespace core {

void checkFailed(std::string_view expression, std::string_view message,
                 std::source_location where) {
    std::fprintf(stderr, "%s:%u: %s(): check `%.*s` failed: %.*s\n", where.file_name(),
                 unsigned(where.line()), where.function_name(), int(expression.size()),
                 expression.data(), int(message.size()), message.data());
    std::fflush(stderr);
    std::abort();
}

} // namespace core
