// KHR_debug output: driver messages go to the log; errors are counted so tests can fail on them.
#pragma once

#include <cstdint>

namespace gl {

/** Enables synchronous KHR_debug output on the current context (needs a debug context). */
void installDebugOutput();

/** GL errors reported through KHR_debug (and glGetError, checked by checkErrors) since start. */
std::uint64_t errorCount();

/** Polls glGetError until clear; each error is logged and counted. Returns how many it found. */
int checkErrors(const char* where);

/** Human-readable GL_VERSION / GL_RENDERER of the current context. */
const char* versionString();
const char* rendererString();

} // namespace gl
