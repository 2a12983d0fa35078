// KHR_debug callback and error accounting.
#include "engine/gl/Debug.h"

#include "engine/core/Log.h"

#include <epoxy/gl.h>

#include <atomic>
#include <string>

namespace gl {
namespace {

std::atomic<std::uint64_t> gErrors{0};

void GLAPIENTRY onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity,
                               GLsizei length, const GLchar* message, const void*) {
    (void)source;
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION)
        return;
    const std::string text = "GL debug (id " + std::to_string(id) +
                             "): " + std::string(message, length > 0 ? std::size_t(length) : 0);
    if (type == GL_DEBUG_TYPE_ERROR) {
        gErrors.fetch_add(1);
        core::logError(text);
    } else if (severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM) {
        core::logWarning(text);
    } else {
        core::logDebug(text);
    }
}

} // namespace

void installDebugOutput() {
    if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43)
        return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onDebugMessage, nullptr);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

LiveObjects liveObjects(std::uint32_t maxName) {
    LiveObjects live;
    for (GLuint name = 1; name <= maxName; ++name) {
        live.buffers += glIsBuffer(name) ? 1 : 0;
        live.textures += glIsTexture(name) ? 1 : 0;
        live.framebuffers += glIsFramebuffer(name) ? 1 : 0;
        live.vertexArrays += glIsVertexArray(name) ? 1 : 0;
        live.programs += glIsProgram(name) ? 1 : 0;
        live.shaders += glIsShader(name) ? 1 : 0;
        live.queries += glIsQuery(name) ? 1 : 0;
    }
    return live;
}

void reportError(const std::string& message) {
    gErrors.fetch_add(1);
    core::logError(message);
}

std::uint64_t errorCount() {
    return gErrors.load();
}

int checkErrors(const char* where) {
    int found = 0;
    for (GLenum error = glGetError(); error != GL_NO_ERROR && found < 64; error = glGetError()) {
        ++found;
        gErrors.fetch_add(1);
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", unsigned(error));
        core::logError(std::string("glGetError ") + code + " at " + where);
    }
    return found;
}

const char* versionString() {
    const auto* v = glGetString(GL_VERSION);
    return v ? reinterpret_cast<const char*>(v) : "?";
}

const char* rendererString() {
    const auto* r = glGetString(GL_RENDERER);
    return r ? reinterpret_cast<const char*>(r) : "?";
}

} // namespace gl
