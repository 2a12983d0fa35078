// Private to the asset module: the exception that carries a load error up to loadGltf(), which
// turns it into a core::Error. Nothing outside asset/ ever sees it.
#pragma once

#include <stdexcept>
#include <string>

namespace asset::detail {

/** Thrown with the element-level message ("skin 0: joint 7 references node 91, ..."); loadGltf
 *  prefixes the function and the file. */
struct LoadError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

[[noreturn]] inline void fail(const std::string& message) {
    throw LoadError(message);
}

} // namespace asset::detail
