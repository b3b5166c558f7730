// Per-frame multiresolution VPL clusters of basic image-space radiosity (Nichols, Shopf & Wyman 2009,
// §3.4): from the RSM's light-space depth and normal min-max pyramid, each VPL is the coarsest patch
// (between minLevel and maxLevel) without a discontinuity, with the summed flux and solid angle of its
// 4^level texels; the survivors are compacted into the VPL cache in patch order (the paper used a geometry
// shader), so that the cache, and the image, are the same in every run. Pass timed as "vpl-cluster".
#pragma once

#include <vector>

#include "gl/frame/rsm.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

struct IsrClusterSettings {
    int minLevel = 2;             // finest patch: 2^minLevel texels per side (the paper's dense sampling)
    int maxLevel = 4;             // coarsest patch: 2^maxLevel texels per side
    float depthThreshold = 0.05f; // relative light-space depth range (max d - min d) / min d of a patch
    float normalThreshold = 0.2f; // largest range of any normal component over a patch
};

class IsrCluster {
public:
    static constexpr int kMaxLevels = 16;

    IsrCluster();
    // The most VPLs `rsm` can give: one per finest-level patch.
    static int capacity(const RsmPass& rsm, int minLevel);
    // Clusters `rsm` (which needs levels >= maxLevel) into `cache` (room for capacity() VPLs) and
    // returns the number of VPLs written (reads the counter back: the gather needs it on the CPU).
    int cluster(const RsmPass& rsm, Buffer& cache, const IsrClusterSettings& settings, PassTimers& timers);
    // VPLs per level of the last cluster() call.
    const std::vector<int>& perLevel() const { return perLevel_; }

private:
    Program program_;
    Program scan_;
    Buffer counter_;
    Buffer slots_; // one uint per finest-level patch: marks, then cache indices
    std::vector<int> perLevel_;
};

} // namespace bounce::gl
