// KHR_debug output: driver messages go to the log; errors are counted so tests can fail on them.
#pragma once

#include <cstdint>
#include <string>

namespace gl {

/** Enables synchronous KHR_debug output on the current context (needs a debug context). */
void installDebugOutput();

/** GL errors reported through KHR_debug (and glGetError, checked by checkErrors) since start. */
std::uint64_t errorCount();

/** Logs `message` as an error and counts it with the GL errors (checks of the gl layer's own). */
void reportError(const std::string& message);

/** Whether draws and dispatches check the current program's storage blocks against the buffers
 *  bound for them through the registry (gl/Registry.h): on in debug builds and wherever the
 *  environment sets GLASS_GL_CHECKS=1 (the test suite does), off with GLASS_GL_CHECKS=0. */
bool bindingChecks();
void setBindingChecks(bool enabled);

/** Polls glGetError until clear; each error is logged and counted. Returns how many it found. */
int checkErrors(const char* where);

/** Live GL objects of the current context, counted by asking the driver about every name up
 *  to `maxName` (glIsBuffer, glIsTexture, ...): independent of the engine's own bookkeeping,
 *  for leak checks (the soak test). */
struct LiveObjects {
    int buffers = 0, textures = 0, framebuffers = 0, vertexArrays = 0, programs = 0,
        shaders = 0, queries = 0;
    int total() const {
        return buffers + textures + framebuffers + vertexArrays + programs + shaders + queries;
    }
};
LiveObjects liveObjects(std::uint32_t maxName = 16384);

/** Human-readable GL_VERSION / GL_RENDERER of the current context. */
const char* versionString();
const char* rendererString();

} // namespace gl
