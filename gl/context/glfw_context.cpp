// A GLFW window with an OpenGL 4.5 core, forward-compatible (debug) context: the demo. GLFW is initialised
// with the first window and terminated with the last.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstring>

#include "gl/context/context_internal.h"

namespace bounce::gl::detail {

namespace {

int liveWindows = 0;

ProcAddress glfwLoader(const char* name)
{
    return glfwGetProcAddress(name);
}

void releaseCurrentGlfw()
{
    if (glfwGetCurrentContext()) glfwMakeContextCurrent(nullptr);
}

const Binding glfwBinding{"glfw", glfwLoader, releaseCurrentGlfw};

std::string lastGlfwError()
{
    const char* text = nullptr;
    glfwGetError(&text);
    return text ? text : "unknown error";
}

// GLFW 3.3 cannot be asked which window system it runs on; its version string names the one it was built
// for ("3.3.8 X11 GLX EGL OSMesa ...").
std::string glfwPlatform()
{
    const char* v = glfwGetVersionString();
    if (std::strstr(v, "Wayland")) return "glfw-wayland";
    if (std::strstr(v, "X11")) return "glfw-x11";
    return "glfw";
}

class GlfwContext final : public Context {
public:
    explicit GlfwContext(GLFWwindow* window) : window_(window)
    {
        ++liveWindows;
        info_.platform = glfwPlatform();
    }

    ~GlfwContext() override
    {
        if (glfwGetCurrentContext() == window_) {
            glfwMakeContextCurrent(nullptr);
            afterRelease(glfwBinding);
        }
        glfwDestroyWindow(window_);
        if (--liveWindows == 0) glfwTerminate();
    }

    void makeCurrent() override
    {
        beforeBind(glfwBinding);
        glfwMakeContextCurrent(window_);
        if (glfwGetCurrentContext() != window_)
            throw ContextError("GLFW: glfwMakeContextCurrent failed: " + lastGlfwError());
        afterBind(glfwBinding);
    }

    void create(const ContextOptions& options)
    {
        beforeBind(glfwBinding);
        glfwMakeContextCurrent(window_);
        if (glfwGetCurrentContext() != window_)
            throw ContextError("GLFW: glfwMakeContextCurrent failed: " + lastGlfwError());
        // The demo measures frame times; vsync would cap them at the display's rate.
        glfwSwapInterval(0);
        finishContext(glfwBinding, info_, options.debug);
    }

    GLFWwindow* window() override { return window_; }
    void swapBuffers() override { glfwSwapBuffers(window_); }

private:
    GLFWwindow* window_;
};

} // namespace

std::unique_ptr<Context> createGlfw(const ContextOptions& options)
{
    if (!glfwInit()) throw ContextError("GLFW: cannot initialise (no display?): " + lastGlfwError());
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!window) {
        const std::string why = lastGlfwError();
        if (liveWindows == 0) glfwTerminate();
        throw ContextError("GLFW: no window with an OpenGL 4.5 core context: " + why);
    }
    auto context = std::make_unique<GlfwContext>(window);
    context->create(options);
    return context;
}

} // namespace bounce::gl::detail
