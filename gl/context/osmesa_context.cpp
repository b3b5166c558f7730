// OSMesa: Mesa's off-screen renderer (llvmpipe), what the tests use by default. Deprecated upstream and
// gone from Mesa 25.1, so nothing may depend on it alone: the library is opened at run time (dlopen), so
// the binary starts, and renders through EGL, on a machine without it (a newer Mesa, a GPU machine that
// carries only its vendor's EGL). Rendering goes to framebuffer objects; the 1x1 colour buffer exists only
// because OSMesaMakeCurrent needs one.
#include <dlfcn.h>

#include <string>
#include <type_traits>

#include <GL/osmesa.h>

#include "gl/context/context_internal.h"

namespace bounce::gl::detail {

namespace {

// The OSMesa entry points Bounce calls, from libOSMesa opened once per process.
struct OsMesaLibrary {
    decltype(&::OSMesaCreateContextAttribs) createContextAttribs = nullptr;
    decltype(&::OSMesaCreateContextExt) createContextExt = nullptr;
    decltype(&::OSMesaDestroyContext) destroyContext = nullptr;
    decltype(&::OSMesaMakeCurrent) makeCurrent = nullptr;
    decltype(&::OSMesaGetCurrentContext) getCurrentContext = nullptr;
    decltype(&::OSMesaGetProcAddress) getProcAddress = nullptr;
    std::string error; // why it could not be opened; empty when every entry point was found
};

const OsMesaLibrary& osMesa()
{
    static const OsMesaLibrary library = [] {
        OsMesaLibrary l;
        void* handle = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_GLOBAL);
        if (!handle) handle = dlopen("libOSMesa.so", RTLD_NOW | RTLD_GLOBAL);
        if (!handle) {
            l.error = "OSMesa is not installed (libOSMesa.so.8: Debian's libosmesa6); use --backend egl";
            return l;
        }
        const auto load = [&](auto& fn, const char* name) {
            fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(handle, name));
            if (!fn && l.error.empty()) l.error = std::string("libOSMesa has no ") + name;
        };
        load(l.createContextAttribs, "OSMesaCreateContextAttribs");
        load(l.createContextExt, "OSMesaCreateContextExt");
        load(l.destroyContext, "OSMesaDestroyContext");
        load(l.makeCurrent, "OSMesaMakeCurrent");
        load(l.getCurrentContext, "OSMesaGetCurrentContext");
        load(l.getProcAddress, "OSMesaGetProcAddress");
        return l;
    }();
    return library;
}

ProcAddress osMesaLoader(const char* name)
{
    return osMesa().getProcAddress(name);
}

void releaseCurrentOsMesa()
{
    if (osMesa().getCurrentContext()) osMesa().makeCurrent(nullptr, nullptr, 0, 0, 0);
}

const Binding osMesaBinding{"osmesa", osMesaLoader, releaseCurrentOsMesa};

class OsMesaContext final : public Context {
public:
    explicit OsMesaContext(OSMesaContext context) : context_(context) { info_.platform = "osmesa"; }

    ~OsMesaContext() override
    {
        if (osMesa().getCurrentContext() == context_) {
            osMesa().makeCurrent(nullptr, nullptr, 0, 0, 0);
            afterRelease(osMesaBinding);
        }
        osMesa().destroyContext(context_);
    }

    void makeCurrent() override
    {
        beforeBind(osMesaBinding);
        bind();
        afterBind(osMesaBinding);
    }

    void create(const ContextOptions& options)
    {
        beforeBind(osMesaBinding);
        bind();
        finishContext(osMesaBinding, info_, options.debug);
    }

private:
    void bind()
    {
        if (!osMesa().makeCurrent(context_, colour_, GL_UNSIGNED_BYTE, 1, 1))
            throw ContextError("OSMesa: OSMesaMakeCurrent failed");
    }

    OSMesaContext context_;
    unsigned char colour_[4] = {};
};

// What a context without version or profile attributes is: "" if even that fails.
std::string describeDefaultContext()
{
    const OSMesaContext probe = osMesa().createContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    if (!probe) return "";
    std::string found;
    unsigned char colour[4] = {};
    beforeBind(osMesaBinding);
    if (osMesa().makeCurrent(probe, colour, GL_UNSIGNED_BYTE, 1, 1)) {
        found = describeCurrentGl(osMesaLoader);
        osMesa().makeCurrent(nullptr, nullptr, 0, 0, 0);
    }
    osMesa().destroyContext(probe);
    return found;
}

} // namespace

std::unique_ptr<Context> createOsMesa(const ContextOptions& options)
{
    if (!osMesa().error.empty()) throw ContextError(osMesa().error);
    // No depth, stencil or accumulation buffer: nothing renders into the OSMesa buffer itself. OSMesa has
    // no debug-context attribute; KHR_debug output works without one.
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_ACCUM_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    const OSMesaContext context = osMesa().createContextAttribs(attribs, nullptr);
    if (!context) {
        const std::string found = describeDefaultContext();
        throw ContextError(found.empty() ? "OpenGL 4.5 core needed; OSMesa refused it and any other context"
                                         : "OpenGL 4.5 core needed; found only " + found +
                                               " through osmesa (OSMesaCreateContextAttribs refused 4.5 core)");
    }
    auto result = std::make_unique<OsMesaContext>(context);
    result->create(options);
    return result;
}

} // namespace bounce::gl::detail

namespace bounce::gl {

std::string osMesaUnavailable()
{
    return detail::osMesa().error;
}

} // namespace bounce::gl
