// One Context interface over the three ways Bounce gets an OpenGL 4.5 core context: headless EGL
// (default: the EGL device platform first, so a real GPU is used when there is one, else Mesa's
// surfaceless platform), OSMesa (what the tests use; deprecated upstream and gone from Mesa 25.1, so
// nothing may depend on it alone), and a GLFW window (the demo).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

struct GLFWwindow;

namespace bounce::gl {

enum class Backend { Egl, OsMesa, Glfw };

// "egl", "osmesa", "glfw"; throws std::invalid_argument naming the allowed values otherwise.
Backend parseBackend(const std::string& name);
const char* backendName(Backend backend);

struct ContextOptions {
    int width = 1280; // window size (GLFW only; headless contexts render into framebuffers)
    int height = 720;
    bool debug = true;   // a KHR_debug context with the callback installed
    bool visible = true; // GLFW only
    std::string title = "Bounce";
    // EGL only: "device" or "surfaceless" to use only that platform; empty: $BOUNCE_EGL_PLATFORM if set,
    // else automatic (a hardware device, then surfaceless, then a software device).
    std::string eglPlatform;
};

struct ContextInfo {
    std::string backend;  // "egl", "osmesa", "glfw"
    std::string platform; // "egl-device", "egl-surfaceless", "egl-device-software", "egl-default",
                          // "osmesa", "glfw-x11", "glfw-wayland"
    std::string renderer; // GL_RENDERER
    std::string vendor;   // GL_VENDOR
    std::string version;  // GL_VERSION
};

// Thrown when no 4.5 core context can be had; the message says what was found (version, renderer).
// The CLI maps it to exit status 2.
struct ContextError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Context {
public:
    // Creates the context, makes it current and loads the GL 4.5 entry points (glad).
    static std::unique_ptr<Context> create(Backend backend, const ContextOptions& options = {});
    virtual ~Context() = default;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // Makes this context current on the calling thread, first unbinding a context of another backend there,
    // and points the GL entry points at it. The entry points are process-wide: contexts of different
    // backends cannot be used from two threads at once. Throws ContextError on failure.
    virtual void makeCurrent() = 0;
    const ContextInfo& info() const { return info_; }

    // Window-only operations; headless contexts do nothing / return null.
    virtual GLFWwindow* window() { return nullptr; }
    virtual void swapBuffers() {}

protected:
    Context() = default;
    ContextInfo info_;
};

// Whether the current context renders on the CPU with Mesa's llvmpipe or softpipe. Some passes work
// around their limits: shader loops end after 65535 iterations (MultiresGather::loopBudget), and fragment
// work is rasterised later than its draw call, so timer scopes wait for it (PassTimers).
bool softwareRasterizer();

// Why this process cannot make an OSMesa context (libOSMesa missing, or without an entry point Bounce
// calls); empty when it can. OSMesa is Mesa's alone and gone from Mesa 25.1: a GPU machine that carries
// only its vendor's EGL has none, and what needs it there skips with this reason.
std::string osMesaUnavailable();

// Whether the current context exposes the GL extension `name` (glGetStringi(GL_EXTENSIONS, i)).
bool hasGlExtension(const char* name);

} // namespace bounce::gl
