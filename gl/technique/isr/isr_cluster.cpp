#include "gl/technique/isr/isr_cluster.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/isr/bindings.h"
#include "gl/technique/isr/vpl_sample.h"

namespace bounce::gl {

IsrCluster::IsrCluster()
    : program_(Program::compute("isr.cluster", "technique/isr/isr_cluster.comp")),
      scan_(Program::compute("isr.clusterScan", "technique/isr/isr_cluster_scan.comp")),
      counter_("isr.vplCount", (1 + kMaxLevels) * sizeof(std::uint32_t))
{}

int IsrCluster::capacity(const RsmPass& rsm, int minLevel)
{
    const int finest = std::max(1, rsm.size() >> minLevel);
    return finest * finest * std::max(1, rsm.viewCount());
}

int IsrCluster::cluster(const RsmPass& rsm, Buffer& cache, const IsrClusterSettings& s, PassTimers& timers)
{
    if (s.maxLevel > rsm.levels() || s.minLevel > s.maxLevel || s.minLevel < 0 || s.maxLevel >= kMaxLevels)
        throw std::logic_error("IsrCluster: levels out of the RSM pyramid's range");
    const int cap = capacity(rsm, s.minLevel);
    if (cache.bytes() < std::size_t(cap) * VplSampler::kVplBytes) throw std::logic_error("VPL cache too small");
    const std::size_t slotBytes = std::size_t(cap) * sizeof(std::uint32_t);
    if (!slots_ || slots_.bytes() < slotBytes) slots_ = Buffer("isr.clusterSlots", slotBytes);
    {
        PassCost cost; // isr_cluster.comp per patch and pass: its pyramid texels at every level it tests
        cost.flops = 60;
        cost.fetches = 8;
        cost.bytesRead = 8 * 16;
        cost.bytesWritten = 8;
        auto t = timers.scope("vpl-cluster", cost);
        // Two passes over the finest patches of every view, and one group of the scan between them.
        const int finest = rsm.size() >> s.minLevel;
        t.expectComputes(rsm.viewCount() > 0
                             ? 2.0 * computeInvocations({finest, finest, rsm.viewCount()}, {8, 8, 1}) + 1024.0
                             : 0.0);
        counter_.clearToZero();
        if (rsm.viewCount() > 0) {
            rsm.bind();
            cache.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_VPL_CACHE);
            counter_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_VPL_COUNT);
            slots_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_CLUSTER_SLOTS);
            program_.set("rsmSize", rsm.size());
            program_.set("minLevel", s.minLevel);
            program_.set("maxLevel", s.maxLevel);
            program_.set("depthThreshold", s.depthThreshold);
            program_.set("normalThreshold", s.normalThreshold);
            program_.set("capacity", unsigned(cap));
            // Mark, scan, write (isr_cluster.comp): VPLs in patch order, the same cache in every run.
            for (int pass = 0; pass < 2; ++pass) {
                if (pass == 1) {
                    scan_.set("patches", unsigned(cap));
                    scan_.use();
                    glDispatchCompute(1, 1, 1);
                    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
                }
                program_.set("writePass", pass);
                program_.use();
                glDispatchCompute(GLuint((finest + 7) / 8), GLuint((finest + 7) / 8), GLuint(rsm.viewCount()));
                glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            }
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    std::uint32_t counts[1 + kMaxLevels] = {};
    counter_.download(0, sizeof(counts), counts);
    perLevel_.assign(counts + 1, counts + 1 + s.maxLevel + 1);
    return int(std::min<std::uint32_t>(counts[0], std::uint32_t(cap)));
}

} // namespace bounce::gl
