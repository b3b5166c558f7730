// What the driver allows a frame, checked before its render targets are allocated: an image larger than
// the driver's textures, viewports or framebuffers, or render targets that need more memory than there
// is, stop the run at once with a ResourceError naming --size, instead of failing (or swapping) a minute
// later when an allocation or a framebuffer gives out.
#pragma once

#include <cstddef>
#include <string>

#include "gl/frame/frame.h"

namespace bounce::gl {

struct DeviceLimits {
    int maxTextureSize = 0;
    int maxViewportWidth = 0, maxViewportHeight = 0;
    int maxFramebufferWidth = 0, maxFramebufferHeight = 0;
    // Memory the frame may take, 0 when unknown: NVIDIA's available video memory
    // (GL_NVX_gpu_memory_info), AMD's free texture memory (GL_ATI_meminfo), or, for a software
    // rasteriser (llvmpipe), the system's available memory (/proc/meminfo MemAvailable).
    std::size_t availableBytes = 0;
    std::string memorySource; // where availableBytes comes from, for messages and records
};

// The current context's limits.
DeviceLimits deviceLimits();

// Bytes per pixel of the frame's own render targets (G-buffer, depth, direct, indirect, composite); the
// specular and emission targets only where the scene needs them (common/gbuffer.glsl).
std::size_t frameTargetBytesPerPixel(bool specular = true, bool emission = true);

// Empty when a frame of these settings fits the limits, else what is wrong, in words that name the
// limit and --size. Pure: tests pass their own limits.
std::string frameFitProblem(const FrameSettings& settings, const DeviceLimits& limits,
                            std::size_t bytesPerPixel = frameTargetBytesPerPixel());

// Throws ResourceError("frame", ...) when frameFitProblem() says anything for the current context.
void checkFrameFits(const FrameSettings& settings, std::size_t bytesPerPixel = frameTargetBytesPerPixel());

} // namespace bounce::gl
