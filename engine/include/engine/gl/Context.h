// A current OpenGL 4.5 core context: headless (EGL, no window system) or a GLFW window, behind
// one interface. This header has no GL types, so the frame graph can name it without GL.
#pragma once

#include "engine/core/Result.h"

#include <glm/glm.hpp>

#include <memory>
#include <string>

namespace gl {

struct ContextOptions {
    glm::ivec2 windowSize{1280, 720}; ///< window contexts only
    std::string title = "glass";
    bool debug = true; ///< KHR_debug context, messages to the log, errors counted
    bool vsync = true; ///< window contexts only
};

class Context {
public:
    virtual ~Context() = default;
    /** "EGL device (NVIDIA ...)", "EGL surfaceless (llvmpipe ...)", "GLFW window". */
    virtual const std::string& description() const = 0;
    virtual bool isHeadless() const = 0;
    /** Size of the default framebuffer in pixels ({0,0} when headless: render offscreen). */
    virtual glm::ivec2 framebufferSize() const = 0;
    virtual void swapBuffers() {}
    virtual void pollEvents() {}
    virtual bool shouldClose() const { return false; }
    /** The GLFWwindow* of a window context (nullptr when headless), for input and UI. */
    virtual void* nativeWindow() const { return nullptr; }
};

/** Headless context with no window system: EGL_EXT_platform_device first (a GPU), then
 *  EGL_MESA_platform_surfaceless (llvmpipe). Fails with one message naming what was tried. */
core::Result<std::unique_ptr<Context>> createHeadlessContext(const ContextOptions& options = {});

/** A GLFW window with a GL 4.5 core context. Fails when there is no display. */
core::Result<std::unique_ptr<Context>> createWindowContext(const ContextOptions& options = {});

/** A window when a display is available and `preferWindow`, else headless. */
core::Result<std::unique_ptr<Context>> createContext(bool preferWindow,
                                                     const ContextOptions& options = {});

} // namespace gl
