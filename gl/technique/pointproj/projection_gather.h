// Importance-driven point projection's gather kernel (Maletz, Wang & Bowers 2011, §3.2, §4 "Microbuffers";
// glsl/technique/pointproj/gather.comp): one work group per shading pixel estimates the 512 clusters'
// importance from N_rnd random points each, allocates N_s samples by the carry rule, splats about 3K points
// into a 32 x 32 hemi-octahedral micro-buffer with Eq. 5's splat sizes, and convolves with the BRDF. At
// pixels ("gather", via AdaptivePixels) or at every stride-th point ("bounce-gather", the multi-bounce
// iteration of §4).
#pragma once

#include <cstdint>
#include <vector>

#include "gl/frame/frame.h"
#include "gl/frame/points/adaptive_pixels.h"
#include "gl/frame/points/point_cloud.h"
#include "gl/frame/ray_caster.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

struct ProjectionSettings {
    int clusters = 512;       // §3.2: "We typically create 512 clusters" (9 kd-tree levels)
    int randomPerCluster = 2; // N_rnd (§3.2: 2)
    int samples = 2048;       // N_s: (2 + 4) x 512 = 3K points projected in all (§4)
    enum class Mode { Importance, Uniform, All } mode = Mode::Importance; // Fig. 9: importance, random, brute force
    int fixedSplat = 0; // Fig. 7: 0 adaptive (Eq. 5), else n x n texels
    // Eq. 3's share of its cluster's area a point stands for: true, 1 / (N_rnd + n_k), the points drawn from
    // the cluster (random ones included); false, the paper's 1 / (N_s p_k) (random points 1 / N_rnd).
    bool shareDrawn = true;
    int holeFill = 4; // passes of the micro-buffer's hole fill; 0: none (the paper)
    // A texel the splats and the fill left empty casts a ray: where it meets the scene, the hit's direct light.
    bool holeRays = true;
};

struct ProjectionStats {
    std::uint32_t targets = 0;
    std::uint32_t projected = 0; // points splatted
    std::uint32_t emptyTexels = 0;
    std::uint32_t uniformFallbacks = 0; // targets whose p_k were all zero
    std::uint32_t clampedSplats = 0;
    std::uint32_t filledTexels = 0; // holes the fill covered
    std::uint32_t holeRays = 0;     // rays cast through the texels left empty (holeRays)
    std::uint32_t holeHits = 0;     // of them, those that met the scene
};

class ProjectionGather {
public:
    static constexpr int kGroup = 128;
    static constexpr int kResolution = 32; // §3.1: "a 32 x 32 texture"

    // With settings.holeRays, the hole rays are cast through the frame's BVH (Frame::rayCaster).
    ProjectionGather(Frame& frame, const PointCloud& cloud, const ProjectionSettings& settings, bool atPoints);

    void gatherPixels(Frame& frame, AdaptivePixels& pixels, int count, const PointCloud& cloud, std::uint32_t seed,
                      PassTimers& timers);
    void gatherPoints(Frame& frame, const PointCloud& cloud, int stride, Buffer& gathered, std::uint32_t seed,
                      PassTimers& timers);
    void clearStats() { stats_.clearToZero(); }
    ProjectionStats stats() const;

private:
    ProjectionSettings settings_;
    mutable double raysPerTarget_ = 0.0, hitsPerTarget_ = 0.0; // of the last stats(), for the cost estimate
    int keyIndexBits_ = 0;
    std::vector<Define> defines_; // the cloud's (GLOSSY_POINTS)
    Buffer texelSolidAngles_, stats_;
    Program pixels_, points_;
    bool atPoints_ = false;
    int lightKinds_ = 0; // of the programs (lightKinds), which the hole rays' shading is built for
    void makePrograms(Frame& frame);
    void followLightKinds(Frame& frame);
    Program makeProgram(Frame& frame, bool atPoints) const;
    PassCost withHoleRays(PassCost c, const Frame& frame, int targets) const;
    void setUniforms(Program& program, Frame& frame, const PointCloud& cloud, std::uint32_t seed);
};

} // namespace bounce::gl
