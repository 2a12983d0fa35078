// Headless GL 4.5 core through EGL with no window system: a device display (NVIDIA, or Mesa's
// software device) first, then Mesa's surfaceless platform.
#include "engine/gl/Context.h"

#include "engine/core/Log.h"
#include "engine/gl/Debug.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <string>
#include <vector>

namespace gl {
namespace {

class EglContext final : public Context {
public:
    EglContext(EGLDisplay display, EGLContext context, std::string description)
        : mDisplay(display), mContext(context), mDescription(std::move(description)) {}
    ~EglContext() override {
        eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(mDisplay, mContext);
        eglTerminate(mDisplay);
    }
    const std::string& description() const override { return mDescription; }
    bool isHeadless() const override { return true; }
    glm::ivec2 framebufferSize() const override { return {0, 0}; }

private:
    EGLDisplay mDisplay;
    EGLContext mContext;
    std::string mDescription;
};

bool hasClientExtension(const char* name) {
    const char* extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!extensions)
        return false;
    const std::string all = std::string(" ") + extensions + " ";
    return all.find(std::string(" ") + name + " ") != std::string::npos;
}

/** Initialises `display` and makes a current GL 4.5 core context on it, or explains why not. */
core::Result<std::unique_ptr<Context>> makeContext(EGLDisplay display, const std::string& platform,
                                                   const ContextOptions& options) {
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor))
        return core::Error{platform + ": eglInitialize failed"};
    if (!eglBindAPI(EGL_OPENGL_API)) {
        eglTerminate(display);
        return core::Error{platform + ": no desktop OpenGL API"};
    }
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    eglChooseConfig(display, configAttributes, &config, 1, &configs);
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                        4,
                                        EGL_CONTEXT_MINOR_VERSION,
                                        5,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_CONTEXT_OPENGL_DEBUG,
                                        options.debug ? EGL_TRUE : EGL_FALSE,
                                        EGL_NONE};
    EGLContext context = eglCreateContext(display, configs > 0 ? config : EGL_NO_CONFIG_KHR,
                                          EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) {
        eglTerminate(display);
        return core::Error{platform + ": no OpenGL 4.5 core context (EGL error 0x" + [] {
            char b[16];
            std::snprintf(b, sizeof b, "%x", unsigned(eglGetError()));
            return std::string(b);
        }() + ")"};
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        eglDestroyContext(display, context);
        eglTerminate(display);
        return core::Error{platform + ": eglMakeCurrent without a surface failed"};
    }
    auto result = std::make_unique<EglContext>(display, context,
                                               "EGL " + platform + " (" + rendererString() + ", " +
                                                   versionString() + ")");
    if (options.debug)
        installDebugOutput();
    return std::unique_ptr<Context>(std::move(result));
}

} // namespace

core::Result<std::unique_ptr<Context>> createHeadlessContext(const ContextOptions& options) {
    std::vector<std::string> tried;
    if (!hasClientExtension("EGL_EXT_platform_base"))
        return core::Error{
            "gl::createHeadlessContext(): EGL has no EGL_EXT_platform_base; "
            "install libegl1 and a driver (libegl-mesa0 + libgl1-mesa-dri for llvmpipe)"};
    if (hasClientExtension("EGL_EXT_platform_device") &&
        hasClientExtension("EGL_EXT_device_enumeration")) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (eglQueryDevicesEXT(16, devices, &count)) {
            for (EGLint i = 0; i < count; ++i) {
                EGLDisplay display =
                    eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                auto context = makeContext(display, "device " + std::to_string(i), options);
                if (context)
                    return context;
                tried.push_back(context.error().message);
            }
        }
        if (count == 0)
            tried.emplace_back("EGL_EXT_platform_device: no devices");
    } else {
        tried.emplace_back("EGL_EXT_platform_device: not supported");
    }
    if (hasClientExtension("EGL_MESA_platform_surfaceless")) {
        EGLDisplay display =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        auto context = makeContext(display, "surfaceless", options);
        if (context)
            return context;
        tried.push_back(context.error().message);
    } else {
        tried.emplace_back("EGL_MESA_platform_surfaceless: not supported");
    }
    std::string message = "gl::createHeadlessContext(): no headless OpenGL 4.5 core context:";
    for (const std::string& t : tried)
        message += " [" + t + "]";
    return core::Error{message};
}

core::Result<std::unique_ptr<Context>> createContext(bool preferWindow,
                                                     const ContextOptions& options) {
    if (preferWindow) {
        auto window = createWindowContext(options);
        if (window)
            return window;
        core::logInfo(window.error().message + "; rendering headless instead");
    }
    return createHeadlessContext(options);
}

} // namespace gl
