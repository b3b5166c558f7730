// The illumination cut (section 3.3): a cut through the photon tree whose nodes stand for their photons
// in the final gather. Per frame, on the GPU:
//   1. E_min = the mean of Eq. 3's E~_p over the nodes of levels `eminLevel` and the one below (the paper:
//      12-13) (cut_emin.comp);
//   2. nodes no deeper than those two levels with E~_p > E_min are selected, bottom-up (cut_select.comp,
//      which says why no deeper), and the selection is made a valid cut: the deepest selected nodes stay,
//      and every region with nothing selected is covered by its topmost node (cut_mark.comp);
//   3. `iterations` refinement passes (the paper: 3-5): each cut node gets its accurate irradiance E_p by
//      density estimation from its k nearest photons at its centre and is replaced by its children where
//      |E_p - E~_p| > `threshold` x E~_p (the paper: 1.2) (cut_refine.comp); a last pass evaluates the
//      nodes the last split made;
//   4. E_p stays cached per cut node, and each node above the cut learns the box its cut descendants'
//      kernels reach (cut_influence.comp), so the gather can walk the tree down to the cut;
//   5. with useGrid(), the cut grid (cut_grid.glsl): per cell of a uniform grid, the cut nodes whose kernel
//      reaches into it, in the walk's order: counted per cell (cut_grid_cells.comp), the counts scanned into
//      starts, the lists filled (cut_grid_cells.comp, FILL) and sorted (cut_grid_sort.comp). Lookups compiled
//      with CUT_GRID read the grid instead of walking the tree, with the same result.
// The coarse cut is listed by a scan in heap order; each refinement pass runs over the nodes the last one
// sent into the cut, listed in their parents' order (cut_enter.comp): the same cut in every run.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/frame/gpu_sort.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"
#include "gl/technique/photon/photon_tree.h"

namespace bounce::gl {

// std430 mirror of CutNode in illumination_cut.glsl.
struct GpuCutNode {
    glm::vec4 irradiance;   // w: 1 once E_p is computed
    glm::vec4 influenceLo;  // w: flags, as a float's value
    glm::vec4 influenceHi;  // w: generation, as a float's value
    glm::vec4 centreRadius; // w: r_p
    glm::vec4 normalRatio;  // w: refinement ratio
    glm::vec4 fallbackLo, fallbackHi;
    glm::vec4 incoming;
};
static_assert(sizeof(GpuCutNode) == 128);
inline constexpr std::uint32_t kCutSelected = 1, kCutAnyBelow = 2, kCutIn = 4, kCutPassed = 8;

struct IlluminationCutSettings {
    int eminLevel = 12;      // E_min from this level and the next (clamped to the tree)
    int iterations = 4;      // refinement passes that may split
    float threshold = 1.2f;  // a node passes when |E_p - E~_p| <= threshold x E~_p
    int densityPhotons = 32; // k of the nearest-photon estimate
};

// `searches` k-nearest-photon searches of glsl/technique/photon/density.glsl in `tree`, as per-scope work.
// A search's length is known only on the GPU: it is estimated from the tree's depth and k.
PassCost nearestPhotonsWork(const PhotonTree& tree, int k, double searches);

class IlluminationCut {
public:
    IlluminationCut();

    // counters: the family's counters buffer (kCounterSlots uints); photons: the tree's photons.
    void build(const PhotonTree& tree, const Buffer& photons, const IlluminationCutSettings& settings, Buffer& counters,
               PassTimers& timers);
    // Binds the per-node cut data at SSBO_PHOTON_CUT.
    void bind() const;
    // From the next build() on, builds the cut grid over `domain` (the scene's bounds), in cubic cells, at
    // most `cells` of them (kMaxGridCells at most); 0 cells or an empty domain: no grid.
    void useGrid(const core::Bounds& domain, int cells);
    static constexpr int kMaxGridCells = 32768; // cut_grid_cells.comp: a node's loop over every cell
    // Binds what cut_lookup.glsl reads: the cut (bind()) and, with the grid, its cells, lists and uniforms.
    void bindLookup(Program& program) const;
    std::uint32_t gridEntries() const { return gridEntries_; } // the lists' length, the last build
    // Whether the last build's lists fit and were sorted, so that lookups read the grid (read back: tests).
    bool gridUsable() const;
    glm::ivec3 gridDims() const { return gridDims_; }

    std::uint32_t size() const { return size_; }
    std::uint32_t coarseSize() const { return coarseSize_; } // before refinement
    float eMin() const { return eMin_; }
    const std::vector<std::uint32_t>& splitsPerIteration() const { return splits_; }
    const Buffer& nodes() const { return nodes_; }
    std::vector<GpuCutNode> download() const;
    // The cut's nodes in heap order, compacted again from the nodes' flags (for tests: the refinement
    // keeps only the list of the nodes entering it); counters: as build()'s.
    std::vector<std::uint32_t> downloadList(const PhotonTree& tree, Buffer& counters);
    std::size_t bytes() const
    {
        return nodes_.bytes() + list_.bytes() + marks_.bytes() + grid_.bytes() + gridCursors_.bytes();
    }

private:
    Program emin_, select_, mark_, flags_, listProgram_, enter_, refine_, influence_;
    GpuScan scan_;
    Buffer nodes_, list_, marks_;
    int refineK_ = 0; // the k refine_ was compiled for
    std::uint32_t size_ = 0, coarseSize_ = 0, nodeCount_ = 0;
    float eMin_ = 0.0f;
    std::vector<std::uint32_t> splits_;

    // The grid's cells and uniforms; none while gridCells_ is 0.
    glm::vec3 gridOrigin_{0.0f};
    float gridInverseCell_ = 0.0f;
    glm::ivec3 gridDims_{0};
    std::uint32_t gridCells_ = 0, gridEntries_ = 0;
    Program gridCount_, gridFill_, gridSort_;
    Buffer grid_, gridCursors_; // cut_grid.glsl's CutGrid; the fill's cursors

    std::uint32_t compact(const PhotonTree& tree, Buffer& counters, PassTimers::Scope& t);
    void buildGrid(Buffer& counters, PassTimers::Scope& t);
    void setGridUniforms(Program& program) const;
};

} // namespace bounce::gl
