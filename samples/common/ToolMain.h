// The tools' main(): runs the tool and turns an exception that escapes it (out of memory, a
// library's throw) into a message and exit status 1 instead of std::terminate.
#pragma once

#include <cstdio>
#include <exception>

namespace tool {

inline int guardedMain(const char* name, int (*run)(int, char**), int argc, char** argv) noexcept {
    try {
        return run(argc, argv);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "%s: %s\n", name, error.what());
    } catch (...) {
        std::fprintf(stderr, "%s: unknown exception\n", name);
    }
    return 1;
}

} // namespace tool
