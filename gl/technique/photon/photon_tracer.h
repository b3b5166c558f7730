// Photon tracing (Wang et al. 2009, section 3.1, "Building Photon Maps"; Jensen 2001): photons from every
// light of the frame (point, spot, directional, emitting triangles), traced through the frame's BVH with
// Russian roulette, stored from the second surface on (direct light is the frame's, from shadow maps),
// put in path order (deterministic), sorted by Hilbert index, then by default put in kd order
// (orderAsKdTree): the input of the photon tree.
// glsl/technique/photon/photon_trace.comp says what happens at a surface.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/frame/frame.h"
#include "gl/frame/gpu_sort.h"
#include "gl/frame/ray_caster.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

// std430 mirror of PhotonEmitter in photon_trace.comp.
struct PhotonEmitter {
    glm::vec4 positionType;
    glm::vec4 directionCos;
    glm::vec4 powerCosInner; // rgb: W per photon
    glm::vec4 v0, v1, v2;
    glm::uvec4 range; // first path, path count
};
static_assert(sizeof(PhotonEmitter) == 112);

// std430 mirror of Photon in glsl/technique/photon/photon.glsl.
struct GpuPhoton {
    glm::vec4 positionPath; // w: path index bits
    glm::vec4 powerIndex;   // w: index within the path, bits
    glm::vec4 incoming;
    glm::vec4 normal;
};
static_assert(sizeof(GpuPhoton) == 64);

// Slots of the counters buffer (photon.glsl: kCounter*).
enum PhotonCounter : std::uint32_t {
    kCounterStaged = 0,
    kCounterStored = 1,
    kCounterScratch = 2,
    kCounterEmin = 3,
    kCounterCutSize = 4,
    kCounterCutSplits = 5,
    kCounterClusters = 6,
    kCounterSeeds = 7,
    kCounterFirst = 8,
    kCounterSlots = 16,
};

// The power a light emits (W, RGB): point 4 pi I, spot I times the solid integral of its falloff
// (2 pi (1 - cos outer) for a hard cone), directional E times the area photons leave from (the marked
// cells of its projection map), an emitting triangle pi L A.
glm::vec3 emittedPower(const LightSource& light, float directionalArea);

// PhotonTracerSettings::firstSurfaceRoulette's masks: bit k for the lights of kind k (gpu_scene.h's kLight*).
inline constexpr std::uint32_t kRouletteEveryLight = 0xFu;
inline constexpr std::uint32_t kRouletteExceptDirectional = kRouletteEveryLight & ~(1u << kLightDirectional);

struct PhotonTracerSettings {
    int photons = 65536; // emitted paths
    int maxBounces = 16; // surfaces one path may reach
    bool russianRoulette = true;
    // Russian roulette at a path's first surface, per light kind (the masks above). A directional light's
    // photons come from the cells where they were seen to be stored (guidedEmission); roulette at the
    // first surface, whose light is direct and not stored, would end most of them there (Sponza's floor:
    // albedo about 0.3). Without it a path's first stored photon carries the power times the first
    // bounce's weight: unequal powers, the same expectation.
    std::uint32_t firstSurfaceRoulette = kRouletteExceptDirectional;
    std::uint32_t seed = 1; // the same in every frame: a moving light moves the same photons
    // Directional lights: photons leave from the cells of a projection map where the light meets the
    // scene (photon_project.comp), or from the whole square across the scene (false).
    bool projectionMap = true;
    // Directional lights: the projection map's cells weighted by where their photons end up (the photons
    // a pilot trace stored per cell; every cell keeps a share, and a photon's power is divided by its
    // cell's weight so the estimate stays unbiased), or every cell alike (false).
    bool guidedEmission = true;
    // Caustic photons (L S+ D): the roughest lobe a caustic path may bounce off; 0: no caustic photons.
    // 0.35 takes glossy lobes such as cornell-glossy's (0.3), whose highlights the final gather's rays
    // sample poorly (photon/README.md, "The caustic map").
    float causticRoughness = 0.35f;
    // The photons in kd order (orderAsKdTree, on the CPU) after the Hilbert sort, so that the photon tree's
    // nodes are the paper's kd-tree cells; false: Hilbert order.
    bool kdOrder = true;
};

// Reorders `photons` so that every node of the photon tree (photon_tree.glsl: node k of level l holds
// [floor(k N / 2^l), floor((k + 1) N / 2^l))) splits at the median of its photons along its bounding box's
// longest side: the tree becomes a balanced kd-tree (the paper's photon tree, after Zhou et al. 2008), whose
// cells stay about as wide as they are long. Deterministic for the same input; a NaN coordinate sorts last.
void orderAsKdTree(std::vector<GpuPhoton>& photons);

// The GGX alpha of causticRoughness as the BRDF clamps it (common/brdf.glsl: at least 1e-3); -1 for 0.
inline float causticAlpha(float causticRoughness)
{
    return causticRoughness > 0.0f ? std::max(causticRoughness * causticRoughness, 1e-3f) : -1.0f;
}

// `walks` closest-hit walks of glsl/common/raycast.glsl through `bvh`, as per-scope work. A walk's length
// is known only on the GPU: it is estimated from the tree's depth (photon_tracer.cpp).
PassCost bvhWalkWork(const core::Bvh& bvh, double walks);

// A directional light's projection map: the square photons may leave from (across the light, behind the
// scene, as wide as the scene's bounding sphere) in gridSize^2 cells, and the cells they leave from.
struct ProjectionMap {
    glm::vec3 direction{0.0f}, corner{0.0f}, axisU{0.0f}, axisV{0.0f};
    float cellSide = 0.0f;
    int gridSize = 0;
    std::vector<std::uint32_t> cells; // marked, widened by one cell; all of them without a projection map
    // Guided emission: per cell of `cells`, the copies of it in the list photons leave from (1 to
    // kMaxCopies), in proportion to the photons its pilot paths stored. Empty: one copy each (no pilot yet,
    // or guidedEmission off).
    std::vector<std::uint32_t> copies;
    static constexpr std::uint32_t kMaxCopies = 1024; // fits the entry's high 16 bits
    // The emission list's entries, cell | copies << 16: a photon picks one uniformly and carries the light's
    // power over the photons times (entries / cells) / copies.
    std::vector<std::uint32_t> entries() const;
};

// Per-cell copies for guided emission from the photons each cell's pilot paths stored: a cell that stored
// the mean count gets kCopiesAtMean copies, more or fewer in proportion, at least one and at most
// ProjectionMap::kMaxCopies. All ones when nothing was stored.
std::vector<std::uint32_t> guidedCopies(const std::vector<double>& storedPerCell);
inline constexpr double kCopiesAtMean = 16.0;

class PhotonTracer {
public:
    explicit PhotonTracer(const PhotonTracerSettings& settings);

    // Traces this frame's photons; afterwards photons() holds storedCount() photons in kd order (Hilbert
    // order without PhotonTracerSettings::kdOrder).
    // counters: the family's counters buffer (kCounterSlots uints).
    void trace(const Frame& frame, const RayCaster& caster, Buffer& counters, PassTimers& timers);

    const Buffer& photons() const { return sorted_; }
    std::uint32_t storedCount() const { return stored_; }
    const std::vector<PhotonEmitter>& emitters() const { return emitters_; }
    // Hilbert indices are taken over this box (the scene's bounds, a little larger).
    glm::vec3 boundsLo() const { return lo_; }
    glm::vec3 boundsExtent() const { return extent_; }
    float sceneSize() const { return size_; }
    int capacity() const { return capacity_; }
    int grownTimes() const { return grown_; }
    // The projection maps of this frame's directional lights, in light order.
    const std::vector<ProjectionMap>& projectionMaps() const { return projections_; }

    // For tests: the power each path left its light with (summed in double), and the photons.
    glm::dvec3 emittedTotal() const;
    std::vector<GpuPhoton> downloadPhotons() const;
    std::size_t bytes() const;

private:
    PhotonTracerSettings settings_;
    Program trace_, place_, permute_, project_;
    bool traceDirectional_ = false; // trace_ was compiled with DIRECTIONAL_LIGHTS
    GpuScan scan_;
    RadixSort sort_;
    Buffer emitterBuffer_, staging_, sorted_, pathCounts_, emitted_, keys_, values_, keysTmp_, valuesTmp_;
    std::vector<PhotonEmitter> emitters_;
    std::vector<int> emitterMaps_; // per emitter: its index in projections_, -1 for a light without a map
    std::vector<ProjectionMap> projections_;
    std::uint64_t projectionsScene_ = 0; // the Frame::version().scene the projection maps were made for
    Buffer cells_;
    Texture cellTexels_; // cells_ as R32UI texels at UNIT_PHOTON_CELLS
    std::uint32_t stored_ = 0;
    int capacity_ = 0, grown_ = 0;
    glm::vec3 lo_{0.0f}, extent_{1.0f};
    float size_ = 1.0f;

    void buildEmitters(const Frame& frame, const RayCaster& caster);
    ProjectionMap project(const Frame& frame, const RayCaster& caster, glm::vec3 direction, float radius);
    void dispatchTrace(const Frame& frame, const RayCaster& caster, Buffer& counters, double& surfaces,
                       double& written);
    void guide();
    void allocate(int capacity);
};

} // namespace bounce::gl
