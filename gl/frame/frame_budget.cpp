#include "gl/frame/frame_budget.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "gl/context/context.h"
#include "gl/gl.h"
#include "gl/resource/resource_error.h"

namespace bounce::gl {

namespace {

// Extension enums not in the generated loader (gl/CMakeLists.txt): both answer in KiB.
constexpr GLenum kGpuMemoryAvailableNvx = 0x9049; // GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
constexpr GLenum kTextureFreeMemoryAti = 0x87FC;  // TEXTURE_FREE_MEMORY_ATI (4 values, the first: total free)

bool hasExtension(const char* name)
{
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i)
        if (const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
            e && std::string(e) == name)
            return true;
    return false;
}

std::size_t memAvailableBytes()
{
    std::ifstream in("/proc/meminfo");
    std::string key;
    std::size_t kib = 0;
    std::string unit;
    while (in >> key >> kib >> unit)
        if (key == "MemAvailable:") return kib * 1024;
    return 0;
}

std::string gib(std::size_t bytes)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f GiB", double(bytes) / double(1ull << 30));
    return buf;
}

} // namespace

DeviceLimits deviceLimits()
{
    DeviceLimits l;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &l.maxTextureSize);
    GLint viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    l.maxViewportWidth = viewport[0];
    l.maxViewportHeight = viewport[1];
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &l.maxFramebufferWidth);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &l.maxFramebufferHeight);
    GLint kib[4] = {0, 0, 0, 0};
    if (hasExtension("GL_NVX_gpu_memory_info")) {
        glGetIntegerv(kGpuMemoryAvailableNvx, kib);
        l.availableBytes = std::size_t(kib[0]) * 1024;
        l.memorySource = "available video memory (GL_NVX_gpu_memory_info)";
    } else if (hasExtension("GL_ATI_meminfo")) {
        glGetIntegerv(kTextureFreeMemoryAti, kib);
        l.availableBytes = std::size_t(kib[0]) * 1024;
        l.memorySource = "free texture memory (GL_ATI_meminfo)";
    } else if (softwareRasterizer()) {
        l.availableBytes = memAvailableBytes();
        l.memorySource = "available system memory (software rasteriser; /proc/meminfo)";
    }
    return l;
}

std::size_t frameTargetBytesPerPixel(bool specular, bool emission)
{
    // Frame::allocateTargets: geometry (RG32UI), diffuse (RGBA16F), specular and emission (RGBA16F) where
    // the scene needs them, depth (32F), direct, indirect, composite (RGBA32F).
    return 8 + 8 + (specular ? 8 : 0) + (emission ? 8 : 0) + 4 + 16 + 16 + 16;
}

std::string frameFitProblem(const FrameSettings& s, const DeviceLimits& l, std::size_t bytesPerPixel)
{
    const std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
    const auto over = [&](int limit, const char* name) {
        return "--size " + size + " is larger than the driver's " + name + " (" + std::to_string(limit) + ")";
    };
    if (l.maxTextureSize > 0 && (s.width > l.maxTextureSize || s.height > l.maxTextureSize))
        return over(l.maxTextureSize, "GL_MAX_TEXTURE_SIZE");
    if (l.maxViewportWidth > 0 && (s.width > l.maxViewportWidth || s.height > l.maxViewportHeight))
        return over(std::max(l.maxViewportWidth, l.maxViewportHeight), "GL_MAX_VIEWPORT_DIMS");
    if (l.maxFramebufferWidth > 0 && (s.width > l.maxFramebufferWidth || s.height > l.maxFramebufferHeight))
        return over(std::max(l.maxFramebufferWidth, l.maxFramebufferHeight), "GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT");
    const std::size_t needed = std::size_t(s.width) * std::size_t(s.height) * bytesPerPixel;
    // The targets alone may take at most half of what there is: the scene, the shadow maps, the
    // technique's own buffers and the image read back for writing need the rest.
    if (l.availableBytes > 0 && needed > l.availableBytes / 2)
        return "--size " + size + ": the frame's render targets alone need " + gib(needed) + " (" +
               std::to_string(bytesPerPixel) + " bytes per pixel), more than half of the " + gib(l.availableBytes) +
               " of " + l.memorySource;
    return "";
}

void checkFrameFits(const FrameSettings& settings, std::size_t bytesPerPixel)
{
    if (const std::string problem = frameFitProblem(settings, deviceLimits(), bytesPerPixel); !problem.empty())
        throw ResourceError("frame", problem);
}

} // namespace bounce::gl
