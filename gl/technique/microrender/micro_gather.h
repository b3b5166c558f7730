// Micro-rendering's gather kernel (Ritschel et al. 2009, §2.2-2.3, §3.2; glsl/technique/microrender/
// gather.comp): one work group per gather sample traverses the point hierarchy, rasterises the cut into an
// importance-warped micro-buffer in shared memory, ray casts the post-traversal list through the frame's
// BVH, and convolves. At pixels ("gather", via PixelGather) or at every stride-th point of the cloud
// ("bounce-gather", the multi-bounce iteration of §4).
#pragma once

#include <array>
#include <cstdint>

#include "core/brdf_warp.h"
#include "gl/frame/frame.h"
#include "gl/frame/points/pixel_gather.h"
#include "gl/frame/points/point_cloud.h"
#include "gl/frame/ray_caster.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"
#include "gl/technique/microrender/point_hierarchy.h"

namespace bounce::gl {

struct MicroGatherSettings {
    int resolution = 24; // micro-buffer side: 8, 16 or 24 (§5: "24 x 24 pixels ... is the maximum we can fit")
    bool warp = true;    // importance warping by the BRDF (§2.3); false: the Nusselt (cosine) mapping
    bool rayCast = true; // the post-traversal list and its rays (§2.2); false: large leaves rasterised as points
    // The rays against the listed leaves' discs only, where the list is not empty (the paper), rather than
    // through the scene's triangles where the list is not empty and at every hole.
    bool rayDiscs = false;
    // With the rays through the triangles: also one through every micro-pixel a silhouette crosses, whose
    // answer stands (gather.comp, "Silhouettes"): where the rasterised nodes do not fill it, and with
    // silhouetteDepths also where they lie at different depths. false: the paper's point rasterisation,
    // which dilates silhouettes by up to a micro-pixel.
    bool silhouetteRays = true;
    bool silhouetteDepths = true;
    // A node is rasterised once its solid angle is at most cut x the micro-pixel's at its direction (§2.2:
    // 1). Larger values rasterise coarser nodes (fewer node centres per pixel: less of the silhouette
    // dilation of point rasterisation) and leave holes that the rays fill.
    float cut = 1.0f;
    // Run the kernel up to this stage only (1 warp, 2 cut and rasterisation, 3 rays, 4 convolution): the
    // time split by stage of §5 from the differences; below 4 the image is black.
    int stages = 4;
    // When not 0, the cut is walked level by level by the whole group from two shared queues of this many
    // nodes (gather.comp, CUT_QUEUE; at least kGroup, made even) rather than one subtree per invocation:
    // the same cut, without waiting for the longest walk.
    int cutQueue = 0;
};

// gather.comp's counters of the last pixel gather.
struct MicroStats {
    std::uint32_t samples = 0;       // gather samples (micro-buffers)
    std::uint32_t withList = 0;      // micro-buffers whose post-traversal list was not empty (cast a ray per pixel)
    std::uint32_t listOverflows = 0; // lists that held more leaves than LIST_CAP
    std::uint32_t emptyPixels = 0;   // micro-pixels nothing covered
    std::uint32_t visited = 0;       // hierarchy nodes visited
    std::uint32_t rasterised = 0;    // nodes rasterised
    std::uint32_t rays = 0;          // rays cast
    std::uint32_t rayPixels = 0;     // micro-pixels a ray hit took
};

class MicroGather {
public:
    static constexpr int kGroup = 64; // invocations per gather sample: subtrees under hierarchy level 6

    MicroGather(Frame& frame, const MicroGatherSettings& settings, const PointHierarchy& hierarchy, bool atPoints);

    void gatherPixels(Frame& frame, PixelGather& targets, const PointCloud& cloud, const PointHierarchy& hierarchy,
                      const RayCaster& caster, PassTimers& timers);
    // Diffuse light gathered at points 0, stride, 2 stride ... into `gathered` (vec4 each).
    void gatherPoints(Frame& frame, const PointCloud& cloud, const PointHierarchy& hierarchy, const RayCaster& caster,
                      int stride, Buffer& gathered, PassTimers& timers);
    const MicroStats& stats() const { return stats_; }
    std::size_t tableBytes() const { return tables_.bytes(); }
    void setCut(float cut) { settings_.cut = cut; }

private:
    MicroGatherSettings settings_;
    core::BrdfWarpTables cpuTables_;
    Buffer tables_, statsBuffer_;
    Program pixels_, points_;
    MicroStats stats_;
    void setUniforms(Program& program, Frame& frame, const PointHierarchy& hierarchy);
    void bindCommon(Frame& frame, const PointCloud& cloud, const PointHierarchy& hierarchy, const RayCaster& caster);
    bool atPoints_ = false;
    int lightKinds_ = 0; // of the programs (lightKinds), which the ray-cast micro-pixels' shading is built for
    void makePrograms(Frame& frame, const PointHierarchy& hierarchy);
    Program makeProgram(Frame& frame, const PointHierarchy& hierarchy, bool atPoints) const;
};

} // namespace bounce::gl
