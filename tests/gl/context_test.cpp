// The context layer: each backend gives an OpenGL 4.5 core context, backends follow one another (and
// alternate) in one process, the debug callback counts errors, compute shaders run. Raw GL on purpose:
// this is the layer gl/resource/ stands on. llvmpipe has two cores here, so every workload is tiny.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/context/context.h"
#include "gl/context/context_internal.h"
#include "gl/debug.h"
#include "gl/gl.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce::gl {
namespace {

ContextOptions headless(const std::string& eglPlatform = "")
{
    ContextOptions options;
    options.width = 64;
    options.height = 64;
    options.visible = false;
    options.eglPlatform = eglPlatform;
    return options;
}

bool hasDisplay()
{
    const char* display = std::getenv("DISPLAY");
    return display && *display;
}

// The current context is 4.5 core, and its info says which backend made it.
void expectCore45(const Context& context, const std::string& backend)
{
    const ContextInfo& info = context.info();
    EXPECT_EQ(info.backend, backend);
    EXPECT_FALSE(info.renderer.empty());
    EXPECT_FALSE(info.vendor.empty());
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45) << info.version;
    EXPECT_NE(profile & GL_CONTEXT_CORE_PROFILE_BIT, 0) << info.version;
    std::printf("[ context  ] %s (%s): %s | %s | %s\n", info.backend.c_str(), info.platform.c_str(),
                info.renderer.c_str(), info.vendor.c_str(), info.version.c_str());
}

// For tests without the fixture: no GL error and no counted debug message since the last reset.
void expectNoGlErrors(const char* where)
{
    checkGlError(where);
    std::string messages;
    for (const DebugMessage& m : takeDebugErrors()) messages += "\n  " + m.text;
    EXPECT_TRUE(messages.empty()) << where << ":" << messages;
}

// Writes i + 1 into element i of a shader storage buffer with a compute shader and reads the buffer back.
std::vector<GLuint> countUpOnGpu(GLuint count)
{
    const char* source = R"(#version 450 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer Result { uint values[]; };
uniform uint count;
void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i < count) values[i] = i + 1u;
}
)";
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    char log[1024] = {};
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    EXPECT_TRUE(ok) << log;
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    EXPECT_TRUE(ok) << log;
    labelObject(GL_PROGRAM, program, "context_test.countUp");

    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, count * sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glClearNamedBufferData(buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    labelObject(GL_BUFFER, buffer, "context_test.result");

    glUseProgram(program);
    glProgramUniform1ui(program, glGetUniformLocation(program, "count"), count);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    glDispatchCompute((count + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<GLuint> values(count);
    glGetNamedBufferSubData(buffer, 0, GLsizeiptr(count * sizeof(GLuint)), values.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glUseProgram(0);
    glDeleteBuffers(1, &buffer);
    glDeleteProgram(program);
    return values;
}

void expectCountsUp(const std::vector<GLuint>& values)
{
    for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], i + 1) << "element " << i;
}

// A 4x4 texture framebuffer cleared to one colour: something owned by one context, to read back later.
struct ColourTarget {
    GLuint texture = 0, framebuffer = 0;

    explicit ColourTarget(const float (&rgba)[4])
    {
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        glTextureStorage2D(texture, 1, GL_RGBA8, 4, 4);
        glCreateFramebuffers(1, &framebuffer);
        glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
        clear(rgba);
    }
    void clear(const float (&rgba)[4]) { glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, rgba); }
    std::vector<unsigned char> read() const
    {
        std::vector<unsigned char> texel(4);
        glGetTextureSubImage(texture, 0, 1, 1, 0, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(texel.size()),
                             texel.data());
        return texel;
    }
    void destroy()
    {
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteTextures(1, &texture);
    }
};

const std::vector<unsigned char> kRed = {255, 0, 0, 255}, kGreen = {0, 255, 0, 255}, kBlue = {0, 0, 255, 255};

// OSMesa is Mesa's alone: a GPU machine with only its vendor's EGL has none, and the tests that need it
// skip there with the reason (BOUNCE_TEST_BACKEND=egl runs every GL suite on such a machine).
#define SKIP_WITHOUT_OSMESA()                                                                                          \
    if (const std::string why = osMesaUnavailable(); !why.empty()) GTEST_SKIP() << why

TEST(ContextTest, OsMesaGivesCore45)
{
    SKIP_WITHOUT_OSMESA();
    resetDebugErrors();
    const auto context = Context::create(Backend::OsMesa, headless());
    EXPECT_EQ(context->info().platform, "osmesa");
    expectCore45(*context, "osmesa");
    expectNoGlErrors("osmesa");
}

TEST(ContextTest, EglGivesCore45)
{
    resetDebugErrors();
    const auto context = Context::create(Backend::Egl, headless());
    EXPECT_EQ(context->info().platform.rfind("egl-", 0), 0u) << context->info().platform;
    expectCore45(*context, "egl");
    expectNoGlErrors("egl");
}

TEST(ContextTest, EglSurfacelessGivesCore45)
{
    resetDebugErrors();
    const auto context = Context::create(Backend::Egl, headless("surfaceless"));
    EXPECT_EQ(context->info().platform, "egl-surfaceless");
    expectCore45(*context, "egl");
    expectNoGlErrors("egl-surfaceless");
}

// The device platform: a GPU where there is one, else Mesa's software device (EGL_MESA_device_software).
TEST(ContextTest, EglDeviceGivesCore45)
{
    resetDebugErrors();
    const auto context = Context::create(Backend::Egl, headless("device"));
    EXPECT_EQ(context->info().platform.rfind("egl-device", 0), 0u) << context->info().platform;
    expectCore45(*context, "egl");
    expectCountsUp(countUpOnGpu(64));
    expectNoGlErrors("egl-device");
}

// The client extensions two drivers really report: Mesa 22.3 names device enumeration on its own,
// NVIDIA 580 only inside EGL_EXT_device_base; both enumerate devices. Without the platform, neither.
TEST(ContextTest, DeviceEnumerationReadFromEitherExtension)
{
    const char* mesa = "EGL_EXT_device_base EGL_EXT_device_enumeration EGL_EXT_device_query EGL_EXT_platform_base "
                       "EGL_KHR_client_get_all_proc_addresses EGL_EXT_client_extensions EGL_KHR_debug "
                       "EGL_EXT_platform_device EGL_EXT_platform_wayland EGL_MESA_platform_surfaceless";
    const char* nvidia = "EGL_EXT_platform_base EGL_EXT_device_base EGL_KHR_client_get_all_proc_addresses "
                         "EGL_EXT_client_extensions EGL_KHR_debug EGL_KHR_platform_x11 EGL_EXT_platform_x11 "
                         "EGL_EXT_platform_device EGL_MESA_platform_surfaceless EGL_EXT_explicit_device";
    EXPECT_TRUE(detail::eglCanEnumerateDevices(mesa));
    EXPECT_TRUE(detail::eglCanEnumerateDevices(nvidia));
    EXPECT_FALSE(detail::eglCanEnumerateDevices("EGL_EXT_device_base EGL_MESA_platform_surfaceless"));
    EXPECT_FALSE(detail::eglCanEnumerateDevices("EGL_EXT_device_base_x EGL_EXT_platform_device"));
    EXPECT_FALSE(detail::eglCanEnumerateDevices(nullptr));
}

TEST(ContextTest, NamesAreChecked)
{
    EXPECT_EQ(parseBackend("egl"), Backend::Egl);
    EXPECT_EQ(parseBackend("osmesa"), Backend::OsMesa);
    EXPECT_EQ(parseBackend("glfw"), Backend::Glfw);
    EXPECT_THROW(parseBackend("vulkan"), std::invalid_argument);
    EXPECT_THROW(Context::create(Backend::Egl, headless("wayland")), ContextError);
}

// One process, one backend after the other, both orders: each context loads its own entry points and
// destroying one leaves nothing behind that breaks the next.
TEST(ContextTest, BackendsFollowOneAnother)
{
    SKIP_WITHOUT_OSMESA();
    for (const auto& order : {std::vector{Backend::OsMesa, Backend::Egl}, std::vector{Backend::Egl, Backend::OsMesa}})
        for (const Backend backend : order) {
            SCOPED_TRACE(backendName(backend));
            resetDebugErrors();
            const auto context = Context::create(backend, headless());
            expectCore45(*context, backendName(backend));
            expectCountsUp(countUpOnGpu(64));
            expectNoGlErrors(backendName(backend));
        }
}

// Two live contexts of different backends, made current in turn: each sees its own objects, through
// entry points reloaded for it (and, for EGL and GLX under glvnd, only after the other was unbound).
void alternate(Backend first, Backend second)
{
    resetDebugErrors();
    const auto one = Context::create(first, headless());
    ColourTarget a({1, 0, 0, 1});
    const auto two = Context::create(second, headless());
    ColourTarget b({0, 1, 0, 1});

    one->makeCurrent();
    EXPECT_EQ(a.read(), kRed);
    a.clear({0, 0, 1, 1});
    two->makeCurrent();
    EXPECT_EQ(b.read(), kGreen);
    expectCountsUp(countUpOnGpu(64));
    one->makeCurrent();
    EXPECT_EQ(a.read(), kBlue);
    expectCountsUp(countUpOnGpu(64));
    a.destroy();
    two->makeCurrent();
    b.destroy();
    expectNoGlErrors("alternating contexts");
}

TEST(ContextTest, BackendsAlternateWhileBothLive)
{
    SKIP_WITHOUT_OSMESA();
    alternate(Backend::OsMesa, Backend::Egl);
}

TEST(ContextTest, GlfwAlternatesWithHeadlessBackends)
{
    if (!hasDisplay()) GTEST_SKIP() << "DISPLAY is not set; run under xvfb-run -a";
    {
        SCOPED_TRACE("glfw, egl");
        alternate(Backend::Glfw, Backend::Egl);
    }
    SKIP_WITHOUT_OSMESA();
    SCOPED_TRACE("osmesa, glfw");
    alternate(Backend::OsMesa, Backend::Glfw);
}

class ContextGlTest : public GlTest {};

// A deliberate error (an invalid texture target) reaches the callback synchronously, is counted with its
// type, and is gone after a reset, so the fixture's own check at the end of the test passes.
TEST_F(ContextGlTest, DebugCallbackCountsDeliberateError)
{
    ASSERT_EQ(debugErrorCount(), 0);
    std::fprintf(stderr, "[ expected ] a GL_INVALID_ENUM from glBindTexture follows\n");
    glBindTexture(0x1234, 0);
    ASSERT_EQ(debugErrorCount(), 1);
    const std::vector<DebugMessage> messages = takeDebugErrors();
    ASSERT_EQ(messages.size(), 1u);
    EXPECT_EQ(messages[0].type, unsigned(GL_DEBUG_TYPE_ERROR));
    EXPECT_EQ(messages[0].source, unsigned(GL_DEBUG_SOURCE_API));
    EXPECT_FALSE(messages[0].text.empty());
    EXPECT_EQ(debugErrorCount(), 0);

    // The same error is still in glGetError's flag; checkGlError counts it too.
    EXPECT_FALSE(checkGlError("the deliberate glBindTexture"));
    EXPECT_EQ(debugErrorCount(), 1);
    EXPECT_TRUE(checkGlError("after the error was read"));
    resetDebugErrors();
    EXPECT_EQ(debugErrorCount(), 0);
}

TEST_F(ContextGlTest, ComputeShaderWritesStorageBuffer)
{
    expectCountsUp(countUpOnGpu(200)); // not a multiple of the group size: the bounds check matters
}

TEST_F(ContextGlTest, LabelsReachTheDriver)
{
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    labelObject(GL_BUFFER, buffer, "gbuffer.normals");
    labelObject(GL_BUFFER, buffer, std::string(1000, 'x')); // longer than some drivers allow: clipped
    char label[2048] = {};
    GLsizei length = 0;
    glGetObjectLabel(GL_BUFFER, buffer, sizeof label, &length, label);
    EXPECT_EQ(std::string(label, std::size_t(length)), std::string(255, 'x'));
    glDeleteBuffers(1, &buffer);
}

// Needs an X server: the CI runs the suite under `xvfb-run -a`.
TEST(ContextTest, GlfwHiddenWindowGivesCore45)
{
    if (!hasDisplay()) GTEST_SKIP() << "DISPLAY is not set; run under xvfb-run -a";
    resetDebugErrors();
    const auto context = Context::create(Backend::Glfw, headless());
    EXPECT_EQ(context->info().platform, "glfw-x11");
    ASSERT_NE(context->window(), nullptr);
    expectCore45(*context, "glfw");
    expectCountsUp(countUpOnGpu(64));
    context->swapBuffers();
    expectNoGlErrors("glfw");
}

// Creating and destroying each kind of context three times in a row: each new context works (a 4.5 core
// context whose compute shader counts up, no GL error), nothing of the destroyed one gets in the way, and
// OSMesa (what the tests use) is there wherever osMesaUnavailable() does not say why not. What it costs is reported (timings are never asserted).
TEST(ContextTest, RepeatedCreationWorksAndReportsTimes)
{
    struct Kind {
        const char* name;
        Backend backend;
        std::string eglPlatform;
    };
    std::vector<Kind> kinds = {{"egl-surfaceless", Backend::Egl, "surfaceless"},
                               {"egl-device", Backend::Egl, "device"}};
    if (const std::string why = osMesaUnavailable(); why.empty())
        kinds.insert(kinds.begin(), {"osmesa", Backend::OsMesa, ""});
    else
        std::printf("[ skipped  ] osmesa: %s\n", why.c_str());
    if (hasDisplay()) kinds.push_back({"glfw", Backend::Glfw, ""});
    int available = 0;
    for (const Kind& kind : kinds) {
        std::vector<double> ms;
        for (int i = 0; i < 3; ++i) {
            const auto start = std::chrono::steady_clock::now();
            std::unique_ptr<Context> context;
            try {
                context = Context::create(kind.backend, headless(kind.eglPlatform));
            } catch (const ContextError& e) {
                EXPECT_EQ(i, 0) << kind.name << " worked, then failed on creation " << i + 1 << ": " << e.what();
                EXPECT_NE(kind.backend, Backend::OsMesa) << "the tests' own backend is missing: " << e.what();
                break;
            }
            resetDebugErrors();
            expectCore45(*context, kind.backend == Backend::OsMesa ? "osmesa"
                                   : kind.backend == Backend::Egl  ? "egl"
                                                                   : "glfw");
            expectCountsUp(countUpOnGpu(16));
            expectNoGlErrors((std::string(kind.name) + " creation " + std::to_string(i + 1)).c_str());
            context.reset();
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        if (ms.empty()) {
            std::printf("[ timing   ] %-16s unavailable\n", kind.name);
            continue;
        }
        ++available;
        const double best = *std::min_element(ms.begin(), ms.end());
        std::printf("[ timing   ] %-16s create+use+destroy: first %.1f ms, best of 3 %.1f ms\n", kind.name, ms[0],
                    best);
        RecordProperty(std::string(kind.name) + "_create_destroy_ms", std::to_string(best));
    }
    EXPECT_GE(available, 1);
    resetDebugErrors();
}

} // namespace
} // namespace bounce::gl
