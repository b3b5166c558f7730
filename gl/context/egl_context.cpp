// Headless EGL. Displays are tried in order: hardware devices (EGL_EXT_platform_device), so a real GPU
// is used when there is one; Mesa's surfaceless platform; Mesa's software device; the default display.
// The first that gives a 4.5 core context wins. No surface where EGL_KHR_surfaceless_context allows it:
// rendering goes to framebuffer objects, and a 1x1 pbuffer stands in only where it must.
#include <glad/egl.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "gl/context/context_internal.h"

namespace bounce::gl::detail {

namespace {

// EGL_EXT_device_drm's name query; glad is not asked for that extension since only this query needs it.
constexpr EGLint kDrmDeviceFileExt = 0x3233;

std::string eglErrorName(EGLint code)
{
    switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    case EGL_BAD_DEVICE_EXT: return "EGL_BAD_DEVICE_EXT";
    default: {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04x", unsigned(code));
        return std::string("EGL error ") + hex;
    }
    }
}

std::string lastEglError()
{
    return eglErrorName(eglGetError());
}

bool hasExtension(const char* list, const char* name)
{
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

// A stable loader: glad's eglGetProcAddress is a pointer that is reassigned on every EGL load.
ProcAddress eglLoader(const char* name)
{
    return eglGetProcAddress(name);
}

void releaseCurrentEgl()
{
    // Binding and releasing act on the thread's current API, which starts as OpenGL ES on a new thread.
    eglBindAPI(EGL_OPENGL_API);
    const EGLDisplay display = eglGetCurrentDisplay();
    if (display != EGL_NO_DISPLAY) eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

const Binding eglBinding{"egl", eglLoader, releaseCurrentEgl};

// eglTerminate ends every context on a display and a display is one per process, so it is terminated
// only when its last context goes.
std::mutex displayMutex;
std::map<EGLDisplay, int> contextsOnDisplay;

void retainDisplay(EGLDisplay display)
{
    std::lock_guard lock(displayMutex);
    ++contextsOnDisplay[display];
}

void releaseDisplay(EGLDisplay display)
{
    std::lock_guard lock(displayMutex);
    if (--contextsOnDisplay[display] > 0) return;
    contextsOnDisplay.erase(display);
    eglTerminate(display);
}

class EglContext final : public Context {
public:
    // `display` is initialised; from here on this object terminates it when no other context uses it.
    EglContext(EGLDisplay display, const std::string& platform) : display_(display)
    {
        retainDisplay(display);
        info_.platform = platform;
    }

    ~EglContext() override
    {
        eglBindAPI(EGL_OPENGL_API);
        if (context_ != EGL_NO_CONTEXT && eglGetCurrentContext() == context_) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            afterRelease(eglBinding);
        }
        if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
        if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
        releaseDisplay(display_);
    }

    void makeCurrent() override
    {
        beforeBind(eglBinding);
        eglBindAPI(EGL_OPENGL_API);
        if (!eglMakeCurrent(display_, surface_, surface_, context_))
            throw ContextError("EGL (" + info_.platform + "): eglMakeCurrent failed: " + lastEglError());
        afterBind(eglBinding);
    }

    void create(const ContextOptions& options)
    {
        // The display's own version and extensions decide what follows; glad loads the entry points of both.
        const int eglVersion = gladLoaderLoadEGL(display_);
        if (!eglVersion) throw ContextError("EGL entry points could not be loaded for this display");
        if (!eglBindAPI(EGL_OPENGL_API)) throw ContextError("no desktop OpenGL (eglBindAPI: " + lastEglError() + ")");
        const bool surfaceless = GLAD_EGL_KHR_surfaceless_context;
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!surfaceless || !GLAD_EGL_KHR_no_config_context) {
            // Headless configs have no window bit, which EGL_SURFACE_TYPE asks for by default.
            const EGLint attribs[] = {EGL_SURFACE_TYPE, surfaceless ? 0 : EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT, EGL_NONE};
            EGLint count = 0;
            if (!eglChooseConfig(display_, attribs, &config, 1, &count))
                throw ContextError("eglChooseConfig failed: " + lastEglError());
            if (count < 1) throw ContextError("no EGL config renders desktop OpenGL");
        }
        if (!surfaceless) {
            const EGLint attribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            surface_ = eglCreatePbufferSurface(display_, config, attribs);
            if (surface_ == EGL_NO_SURFACE)
                throw ContextError("no surfaceless contexts, and a 1x1 pbuffer was refused: " + lastEglError());
        }
        createContext(config, eglVersion, options.debug);
        beforeBind(eglBinding);
        if (!eglMakeCurrent(display_, surface_, surface_, context_))
            throw ContextError("eglMakeCurrent failed: " + lastEglError());
        finishContext(eglBinding, info_, options.debug);
    }

private:
    void createContext(EGLConfig config, int eglVersion, bool debug)
    {
        // EGL 1.5 has the version, profile and debug attributes; EGL_KHR_create_context has the same
        // tokens except debug, which is a flag there. Without either, whatever comes is checked later.
        std::vector<EGLint> attribs;
        const bool egl15 = eglVersion >= GLAD_MAKE_VERSION(1, 5);
        if (egl15 || GLAD_EGL_KHR_create_context) {
            attribs = {EGL_CONTEXT_MAJOR_VERSION,       4,
                       EGL_CONTEXT_MINOR_VERSION,       5,
                       EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
            if (debug && egl15) attribs.insert(attribs.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
            if (debug && !egl15)
                attribs.insert(attribs.end(), {EGL_CONTEXT_FLAGS_KHR, EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR});
        }
        attribs.push_back(EGL_NONE);
        context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, attribs.data());
        if (context_ == EGL_NO_CONTEXT) {
            const std::string refusal = "eglCreateContext for 4.5 core: " + lastEglError();
            const std::string found = describeDefaultContext(config);
            throw ContextError(found.empty() ? "OpenGL 4.5 core needed; " + refusal
                                             : "OpenGL 4.5 core needed; found only " + found + " through " +
                                                   info_.platform + " (" + refusal + ")");
        }
    }

    // What a context without version or profile attributes is: "" if even that fails.
    std::string describeDefaultContext(EGLConfig config)
    {
        const EGLint none[] = {EGL_NONE};
        const EGLContext probe = eglCreateContext(display_, config, EGL_NO_CONTEXT, none);
        if (probe == EGL_NO_CONTEXT) return "";
        std::string found;
        beforeBind(eglBinding);
        if (eglMakeCurrent(display_, surface_, surface_, probe)) {
            found = describeCurrentGl(eglLoader);
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        }
        eglDestroyContext(display_, probe);
        return found;
    }

    EGLDisplay display_;
    EGLContext context_ = EGL_NO_CONTEXT;
    EGLSurface surface_ = EGL_NO_SURFACE;
};

} // namespace

bool eglCanEnumerateDevices(const char* client)
{
    return (hasExtension(client, "EGL_EXT_device_enumeration") || hasExtension(client, "EGL_EXT_device_base")) &&
           hasExtension(client, "EGL_EXT_platform_device");
}

namespace {

struct Candidate {
    EGLDisplay display;
    std::string platform; // what ContextInfo::platform will say
    std::string label;    // what an error message says about it
};

// The displays to try, best first. `only` is "", "device" or "surfaceless".
std::vector<Candidate> candidateDisplays(const std::string& only)
{
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    std::vector<Candidate> hardware, software, surfaceless;
    if (only != "surfaceless" && eglCanEnumerateDevices(client) && eglQueryDevicesEXT && eglGetPlatformDisplayEXT) {
        EGLint count = 0;
        eglQueryDevicesEXT(0, nullptr, &count);
        std::vector<EGLDeviceEXT> devices(std::size_t(count > 0 ? count : 0));
        if (count > 0 && !eglQueryDevicesEXT(count, devices.data(), &count)) count = 0;
        for (EGLint i = 0; i < count; ++i) {
            const char* extensions =
                eglQueryDeviceStringEXT ? eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS) : nullptr;
            const bool isSoftware = hasExtension(extensions, "EGL_MESA_device_software");
            const char* file = hasExtension(extensions, "EGL_EXT_device_drm")
                                   ? eglQueryDeviceStringEXT(devices[i], kDrmDeviceFileExt)
                                   : nullptr;
            const std::string label = "egl device " + std::to_string(i) +
                                      (isSoftware ? " (software)"
                                       : file     ? std::string(" (") + file + ")"
                                                  : "");
            const EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
            if (display == EGL_NO_DISPLAY) continue;
            if (isSoftware)
                software.push_back({display, "egl-device-software", label});
            else
                hardware.push_back({display, "egl-device", label});
        }
    }
    if (only != "device" && hasExtension(client, "EGL_MESA_platform_surfaceless") && eglGetPlatformDisplayEXT) {
        const EGLDisplay display =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display != EGL_NO_DISPLAY) surfaceless.push_back({display, "egl-surfaceless", "egl-surfaceless"});
    }
    std::vector<Candidate> out = hardware;
    out.insert(out.end(), surfaceless.begin(), surfaceless.end());
    out.insert(out.end(), software.begin(), software.end());
    if (only.empty()) {
        // Whatever the implementation calls its default: on a driver without the extensions above, this
        // may still be a working headless display.
        const EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        const bool tried =
            std::any_of(out.begin(), out.end(), [&](const Candidate& c) { return c.display == display; });
        if (display != EGL_NO_DISPLAY && !tried) out.push_back({display, "egl-default", "egl default display"});
    }
    return out;
}

std::unique_ptr<Context> createOn(const Candidate& candidate, const ContextOptions& options)
{
    EGLint major = 0, minor = 0;
    if (!eglInitialize(candidate.display, &major, &minor))
        throw ContextError("eglInitialize failed: " + lastEglError());
    auto context = std::make_unique<EglContext>(candidate.display, candidate.platform);
    context->create(options);
    return context;
}

} // namespace

std::unique_ptr<Context> createEgl(const ContextOptions& options)
{
    std::string only = options.eglPlatform;
    if (const char* env = std::getenv("BOUNCE_EGL_PLATFORM"); only.empty() && env) only = env;
    if (!only.empty() && only != "device" && only != "surfaceless")
        throw ContextError("unknown EGL platform '" + only + "'; allowed: device, surfaceless");
    // Client extensions first: device enumeration and platform displays exist before any display does.
    if (!gladLoaderLoadEGL(EGL_NO_DISPLAY)) throw ContextError("EGL: libEGL.so.1 could not be loaded");
    const std::vector<Candidate> candidates = candidateDisplays(only);
    std::vector<std::string> failures;
    for (const Candidate& candidate : candidates) {
        try {
            return createOn(candidate, options);
        } catch (const ContextError& e) {
            failures.push_back(candidate.label + ": " + e.what());
        }
    }
    if (failures.empty())
        throw ContextError("EGL: no display to try (no " +
                           (only.empty() ? std::string("device, surfaceless or default") : only) + " display)");
    if (failures.size() == 1) throw ContextError("EGL: " + failures.front());
    std::string message = "EGL: no display gave an OpenGL 4.5 core context; tried ";
    for (std::size_t i = 0; i < failures.size(); ++i) message += (i ? "; " : "") + failures[i];
    throw ContextError(message);
}

} // namespace bounce::gl::detail
