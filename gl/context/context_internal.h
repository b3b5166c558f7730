// Shared by the three context implementations, without GL or window-system headers (OSMesa's and
// GLFW's headers must not meet glad's).
#pragma once

#include <memory>
#include <string>

#include "gl/context/context.h"

namespace bounce::gl::detail {

using ProcAddress = void (*)();
using ProcLoader = ProcAddress (*)(const char* name);

// How one backend binds: where its GL entry points come from and how it unbinds its current context.
// glad's GL function pointers are process-wide, and OSMesa's dispatch (its own libglapi) is not glvnd's
// (EGL, GLX), so switching backends means reloading them. glvnd also refuses to make an EGL context
// current while a GLX one is (and the reverse), so the other backend is unbound first.
struct Binding {
    const char* backend;
    ProcLoader loader;
    void (*release)(); // unbinds this backend's current context from the calling thread
};

// Before a backend makes one of its contexts current: unbinds another backend's current context.
void beforeBind(const Binding& binding);
// After it did: reloads the GL entry points when they were last loaded through another loader.
void afterBind(const Binding& binding);
// When a backend unbinds its context (destruction): the thread has no current context of that backend.
void afterRelease(const Binding& binding);

// Loads the GL 4.5 core entry points through the binding's loader into the current context, fills `info`
// (renderer, vendor, version) and checks for 4.5 core; throws ContextError saying what was found
// otherwise. Installs the debug callback when `debug`.
void finishContext(const Binding& binding, ContextInfo& info, bool debug);

// For error messages when 4.5 core was refused and a default context was made current instead to see what
// there is: "GL_VERSION (GL_RENDERER)", read through `loader` without touching glad's pointers.
std::string describeCurrentGl(ProcLoader loader);

// Whether EGL's client extensions (`eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS)`) let devices be
// enumerated and opened as displays: EGL_EXT_platform_device with EGL_EXT_device_enumeration (Mesa) or
// EGL_EXT_device_base, the older extension that holds enumeration and query (NVIDIA names only this).
bool eglCanEnumerateDevices(const char* clientExtensions);

std::unique_ptr<Context> createEgl(const ContextOptions& options);
std::unique_ptr<Context> createOsMesa(const ContextOptions& options);
std::unique_ptr<Context> createGlfw(const ContextOptions& options);

} // namespace bounce::gl::detail
