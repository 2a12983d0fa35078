// Failure path of ENGINE_CHECK.
#include "engine/core/Check.h"

#include <cstdio>
#include <cstdlib>

namespace core {

void checkFailed(std::string_view expression, std::string_view message, SourceLocation where) {
    std::fprintf(stderr, "%s:%d: %s(): check `%.*s` failed: %.*s\n", where.file, where.line,
                 where.function, int(expression.size()),
                 expression.data(), int(message.size()), message.data());
    std::fflush(stderr);
    std::abort();
}

} // namespace core
