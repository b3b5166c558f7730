#include "gl/context/context.h"

#include <cstring>
#include <stdexcept>

#include "gl/context/context_internal.h"
#include "gl/debug.h"
#include "gl/gl.h"

namespace bounce::gl {

Backend parseBackend(const std::string& name)
{
    if (name == "egl") return Backend::Egl;
    if (name == "osmesa") return Backend::OsMesa;
    if (name == "glfw") return Backend::Glfw;
    throw std::invalid_argument("unknown backend '" + name + "'; allowed: egl, osmesa, glfw");
}

const char* backendName(Backend backend)
{
    switch (backend) {
    case Backend::Egl: return "egl";
    case Backend::OsMesa: return "osmesa";
    case Backend::Glfw: return "glfw";
    }
    return "?";
}

bool softwareRasterizer()
{
    const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string renderer = r ? r : "";
    return renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
}

bool hasGlExtension(const char* name)
{
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && std::strcmp(e, name) == 0) return true;
    }
    return false;
}

std::unique_ptr<Context> Context::create(Backend backend, const ContextOptions& options)
{
    switch (backend) {
    case Backend::Egl: return detail::createEgl(options);
    case Backend::OsMesa: return detail::createOsMesa(options);
    case Backend::Glfw: return detail::createGlfw(options);
    }
    throw ContextError("unknown backend");
}

namespace detail {

namespace {

// The loader glad's GL pointers came from (process-wide, like the pointers), and the backend whose
// context is current on this thread.
ProcLoader loadedWith = nullptr;
thread_local const Binding* bound = nullptr;

std::string glString(GLenum name)
{
    const GLubyte* s = glGetString ? glGetString(name) : nullptr;
    return s ? reinterpret_cast<const char*>(s) : "";
}

} // namespace

void beforeBind(const Binding& binding)
{
    if (bound && bound != &binding) bound->release();
    bound = nullptr;
}

void afterBind(const Binding& binding)
{
    bound = &binding;
    if (loadedWith == binding.loader) return;
    if (!gladLoadGL(binding.loader))
        throw ContextError(std::string("the OpenGL entry points could not be reloaded through ") + binding.backend);
    loadedWith = binding.loader;
}

void afterRelease(const Binding& binding)
{
    if (bound == &binding) bound = nullptr;
}

std::string describeCurrentGl(ProcLoader loader)
{
    const auto getString = reinterpret_cast<PFNGLGETSTRINGPROC>(loader("glGetString"));
    const auto text = [&](GLenum name) {
        const GLubyte* s = getString ? getString(name) : nullptr;
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return text(GL_VERSION) + " (" + text(GL_RENDERER) + ")";
}

void finishContext(const Binding& binding, ContextInfo& info, bool debug)
{
    bound = &binding;
    // Always reload: the pointers may be left over from a destroyed context of the same backend, and the
    // version glad parses is what the check below needs.
    const int version = gladLoadGL(binding.loader);
    loadedWith = version ? binding.loader : nullptr;
    info.backend = binding.backend;
    info.renderer = glString(GL_RENDERER);
    info.vendor = glString(GL_VENDOR);
    info.version = glString(GL_VERSION);
    if (!version)
        throw ContextError("OpenGL 4.5 core needed; no GL version could be read through " + info.platform +
                           " (glGetString(GL_VERSION) failed)");
    const int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
    GLint profile = 0;
    if (major * 10 + minor >= 32) glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    const bool core = (profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    if (major * 10 + minor < 45 || !core)
        throw ContextError("OpenGL 4.5 core needed; found " + std::to_string(major) + "." + std::to_string(minor) +
                           (core ? " core" : " compatibility") + " (" + info.renderer + "; GL_VERSION \"" +
                           info.version + "\") through " + info.platform);
    if (debug) installDebugCallback();
}

} // namespace detail
} // namespace bounce::gl
