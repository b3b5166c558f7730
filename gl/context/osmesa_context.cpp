// OSMesa: Mesa's off-screen renderer (llvmpipe), what the tests use by default. Deprecated upstream and
// gone from Mesa 25.1, so nothing may depend on it alone. Rendering goes to framebuffer objects; the
// 1x1 colour buffer exists only because OSMesaMakeCurrent needs one.
#include <GL/osmesa.h>

#include "gl/context/context_internal.h"

namespace bounce::gl::detail {

namespace {

ProcAddress osMesaLoader(const char* name)
{
    return OSMesaGetProcAddress(name);
}

void releaseCurrentOsMesa()
{
    if (OSMesaGetCurrentContext()) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
}

const Binding osMesaBinding{"osmesa", osMesaLoader, releaseCurrentOsMesa};

class OsMesaContext final : public Context {
public:
    explicit OsMesaContext(OSMesaContext context) : context_(context) { info_.platform = "osmesa"; }

    ~OsMesaContext() override
    {
        if (OSMesaGetCurrentContext() == context_) {
            OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
            afterRelease(osMesaBinding);
        }
        OSMesaDestroyContext(context_);
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
        if (!OSMesaMakeCurrent(context_, colour_, GL_UNSIGNED_BYTE, 1, 1))
            throw ContextError("OSMesa: OSMesaMakeCurrent failed");
    }

    OSMesaContext context_;
    unsigned char colour_[4] = {};
};

// What a context without version or profile attributes is: "" if even that fails.
std::string describeDefaultContext()
{
    const OSMesaContext probe = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    if (!probe) return "";
    std::string found;
    unsigned char colour[4] = {};
    beforeBind(osMesaBinding);
    if (OSMesaMakeCurrent(probe, colour, GL_UNSIGNED_BYTE, 1, 1)) {
        found = describeCurrentGl(osMesaLoader);
        OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    }
    OSMesaDestroyContext(probe);
    return found;
}

} // namespace

std::unique_ptr<Context> createOsMesa(const ContextOptions& options)
{
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
    const OSMesaContext context = OSMesaCreateContextAttribs(attribs, nullptr);
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
