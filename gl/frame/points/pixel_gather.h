// Gathering at a subset of the pixels, shared by the point-based gathers: the frame's multiresolution
// pyramid (gl/frame/multires.h) chooses the gather locations (every pixel at coarsestLevel 0; else patches
// of 2^level pixels, refined where depth or normals jump), a compute pass lists them, the technique
// gathers at each into two flattened illumination buffers (the diffuse part without the receiver's diffuse
// colour, and the glossy part), and the frame's joint bilateral upsampling fills every pixel
// (micro-rendering §2.4, after Sloan et al. 2007). Passes:
//   "minmax-mipmap"  the pyramid (the frame's)
//   "gather-select"  the valid fragments listed (glsl/frame/points/gather_select.comp)
//   "upsample"       the frame's upsampling of both buffers into frame.indirect()
// The gather shader includes glsl/frame/points/gather_target.glsl and calls bindForGather first.
#pragma once

#include <cstdint>

#include "gl/frame/frame.h"
#include "gl/frame/multires.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

// The list of gather targets (SSBO_GATHER_TARGETS: frame/points/gather_select.comp and adaptive_select.comp
// write it, gather_target.glsl reads it): its length in the first word, the targets from byte 8.
constexpr std::size_t kGatherListHeaderBytes = 8;
// Sets the list's length to 0, which the select passes count up.
inline void clearGatherCount(Buffer& list)
{
    const std::uint32_t zero = 0;
    list.update(0, sizeof(zero), &zero);
}

class PixelGather {
public:
    PixelGather(Frame& frame, const MultiresSettings& settings);

    // "minmax-mipmap" and "gather-select"; returns how many targets the gather has (read back: the
    // dispatch is sized by it).
    int select(Frame& frame, PassTimers& timers);
    // Binds the targets, the G-buffer, the pyramid and the illumination images, and sets the uniforms of
    // gather_target.glsl and multires.glsl on `program`.
    void bindForGather(Frame& frame, Program& program);
    // "upsample": both buffers into frame.indirect().
    void upsample(Frame& frame, PassTimers& timers);
    void setThresholds(float depthThreshold, float normalThreshold)
    {
        pyramid_.setThresholds(depthThreshold, normalThreshold);
    }

    int count() const { return count_; }
    const MultiresPyramid& pyramid() const { return pyramid_; }

private:
    MultiresPyramid pyramid_;
    Program select_;
    Buffer targets_; // the gather list
    Texture diffuse_, glossy_;
    int count_ = 0;
    void allocate();
};

// One work group per target, MICRO_GROUP (localSize) invocations each: a 2D dispatch past the
// 65535-group limit of one axis (gather_target.glsl: gatherTargetIndex). Nothing when count is 0.
void dispatchPerTarget(const Program& program, int count, int localSize);
// The invocations dispatchPerTarget(program, count, localSize) runs (PassTimers::Scope::expectComputes).
double perTargetInvocations(int count, int localSize);

} // namespace bounce::gl
