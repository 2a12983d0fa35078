// A GLFW window with a GL 4.5 core context.
#include "engine/gl/Context.h"

#include "engine/gl/Debug.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>

namespace gl {
namespace {

std::string glfwLastError() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown GLFW error";
}

class GlfwContext final : public Context {
public:
    GlfwContext(GLFWwindow* window, std::string description)
        : mWindow(window), mDescription(std::move(description)) {}
    ~GlfwContext() override {
        glfwDestroyWindow(mWindow);
        glfwTerminate();
    }
    const std::string& description() const override { return mDescription; }
    bool isHeadless() const override { return false; }
    glm::ivec2 framebufferSize() const override {
        glm::ivec2 size;
        glfwGetFramebufferSize(mWindow, &size.x, &size.y);
        return size;
    }
    void swapBuffers() override { glfwSwapBuffers(mWindow); }
    void pollEvents() override { glfwPollEvents(); }
    bool shouldClose() const override { return glfwWindowShouldClose(mWindow); }
    void* nativeWindow() const override { return mWindow; }

private:
    GLFWwindow* mWindow;
    std::string mDescription;
};

} // namespace

core::Result<std::unique_ptr<Context>> createWindowContext(const ContextOptions& options) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland))
        return core::Error{
            "gl::createWindowContext(): no display (DISPLAY and WAYLAND_DISPLAY unset)"};
    if (!glfwInit())
        return core::Error{"gl::createWindowContext(): glfwInit failed: " + glfwLastError()};
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(options.windowSize.x, options.windowSize.y,
                                          options.title.c_str(), nullptr, nullptr);
    if (!window) {
        const std::string error = glfwLastError();
        glfwTerminate();
        return core::Error{"gl::createWindowContext(): no GL 4.5 core window: " + error};
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(options.vsync ? 1 : 0);
    auto context = std::make_unique<GlfwContext>(
        window, std::string("GLFW window (") + rendererString() + ", " + versionString() + ")");
    if (options.debug)
        installDebugOutput();
    return std::unique_ptr<Context>(std::move(context));
}

} // namespace gl
