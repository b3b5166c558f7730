#include "gl/technique/photon/shading_clusters.h"

#include <algorithm>
#include <bit>

#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/photon/bindings.h"
#include "gl/technique/photon/photon_tracer.h"

namespace bounce::gl {

namespace {

Program compute(const char* name, const char* file, const std::vector<Define>& defines = {})
{
    return Program::compute(std::string("photon.") + name, std::string("technique/photon/") + file, defines);
}

// quad_error.comp: nodes of more pixels than this per side take one work group of kQuadGroup invocations
// each, smaller ones one invocation each.
constexpr int kQuadGroupSpan = 16, kQuadGroup = 256;

} // namespace

ShadingClusters::ShadingClusters(const ShadingClusterSettings& settings)
    : settings_(settings),
      quadLeaves_(compute("quadLeaves", "quad_leaves.comp")),
      quadReduce_(compute("quadReduce", "quad_reduce.comp")),
      quadError_(compute("quadError", "quad_error.comp")),
      quadErrorGroup_(compute("quadErrorGroup", "quad_error.comp", {{"QUAD_GROUP", std::to_string(kQuadGroup)}})),
      seedDistribute_(compute("seedDistribute", "seed_distribute.comp")),
      seedWrite_(compute("seedWrite", "seed_write.comp")),
      pointKeys_(compute("pointKeys", "point_keys.comp")),
      pointLeaves_(compute("pointLeaves", "point_leaves.comp")),
      pointReduce_(compute("pointReduce", "point_reduce.comp")),
      assign_(compute("kmeansAssign", "kmeans_assign.comp")),
      segments_(compute("kmeansSegments", "kmeans_segments.comp")),
      update_(compute("kmeansUpdate", "kmeans_update.comp")),
      sample_(compute("kmeansSample", "kmeans_sample.comp")),
      marks_(compute("kmeansMarks", "kmeans_marks.comp")),
      survivorsProgram_(compute("kmeansSurvivors", "kmeans_survivors.comp")),
      perPixel_(compute("clustersPerPixel", "clusters_per_pixel.comp"))
{}

void ShadingClusters::allocate(int width, int height)
{
    if (width == width_ && height == height_ && clusters_) return;
    width_ = width;
    height_ = height;
    quadSize_ = int(std::bit_ceil(unsigned(std::max(width, height))));
    quadLevels_ = std::bit_width(unsigned(quadSize_)) - 1;
    std::size_t quadNodes = 0;
    for (int m = 0; m <= quadLevels_; ++m) quadNodes += std::size_t(quadSize_ >> m) * std::size_t(quadSize_ >> m);
    quad_ = Buffer("photon.quadtree", quadNodes * 32);
    seedsBuffer_ =
        Buffer("photon.seeds", std::max(quadNodes * 8, std::size_t(settings_.clusters) * sizeof(GpuCluster)));
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    clusterOfPixel_ = Buffer("photon.clusterOfPixel", pixels * 4);
    clusterOfPixel_.clearToZero();
    const std::size_t k =
        settings_.everyPixel ? std::max<std::size_t>(pixels, 1) : std::size_t(std::max(settings_.clusters, 1));
    clusters_ = Buffer("photon.clusters", k * sizeof(GpuCluster));
    clusters_.clearToZero();
    const std::size_t sortCount = std::max(pixels, std::size_t(std::bit_ceil(unsigned(k))));
    keys_ = Buffer("photon.clusterSortKeys", sortCount * 4);
    values_ = Buffer("photon.clusterSortValues", sortCount * 4);
    keysTmp_ = Buffer("photon.clusterSortKeysTmp", sortCount * 4);
    valuesTmp_ = Buffer("photon.clusterSortValuesTmp", sortCount * 4);
    pointTree_ = Buffer("photon.pointTree", 2 * std::bit_ceil(unsigned(k)) * sizeof(GpuPointNode));
    marksBuffer_ = Buffer("photon.clusterMarks", k * 4);
    havePrevious_ = false;
}

void ShadingClusters::bind() const
{
    clusters_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_CENTRES);
}

void ShadingClusters::setCommon(Program& p) const
{
    p.set("alpha", alpha_);
    p.set("quadSize", quadSize_);
    p.set("quadLevels", quadLevels_);
    p.set("viewport", glm::ivec2(width_, height_));
    p.set("pointTreeDepth", pointDepth_);
}

void ShadingClusters::bindPointTree(Program& program) const
{
    pointTree_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_TREE);
    program.set("pointTreeDepth", pointDepth_);
}

void ShadingClusters::buildQuadtree(bool onlyUnclassified)
{
    quad_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_QUADTREE);
    clusterOfPixel_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_OF_PIXEL);
    for (Program* p : {&quadLeaves_, &quadReduce_, &quadError_, &quadErrorGroup_}) {
        setCommon(*p);
        p->set("onlyUnclassified", onlyUnclassified ? 1 : 0);
    }
    dispatchCompute(quadLeaves_, {quadSize_, quadSize_, 1}, {8, 8, 1});
    for (int level = 1; level <= quadLevels_; ++level) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        quadReduce_.set("level", level);
        dispatchCompute(quadReduce_, {quadSize_ >> level, quadSize_ >> level, 1}, {8, 8, 1});
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    for (int level = 1; level <= quadLevels_; ++level) {
        const int side = quadSize_ >> level;
        if ((1 << level) > kQuadGroupSpan) {
            quadErrorGroup_.set("level", level);
            dispatchCompute(quadErrorGroup_, {side * kQuadGroup, side, 1}, {kQuadGroup, 1, 1});
        } else {
            quadError_.set("level", level);
            dispatchCompute(quadError_, {side, side, 1}, {8, 8, 1});
        }
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void ShadingClusters::placeSeeds(std::uint32_t first, std::uint32_t count, Buffer& counters)
{
    quad_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_QUADTREE);
    seedsBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_SEEDS);
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
    setCommon(seedDistribute_);
    seedDistribute_.set("firstSeed", first);
    seedDistribute_.set("seedCount", count);
    seedDistribute_.set("seed", settings_.seed);
    for (int level = quadLevels_; level >= 0; --level) {
        seedDistribute_.set("level", level);
        dispatchCompute(seedDistribute_, {quadSize_ >> level, quadSize_ >> level, 1}, {8, 8, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    bind();
    setCommon(seedWrite_);
    dispatchCompute(seedWrite_, {width_, height_, 1}, {8, 8, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    counters.download(kCounterSeeds * 4, 4, &seeds_);
}

void ShadingClusters::buildPointTree(bool useSamples, Buffer& counters)
{
    pointDepth_ = count_ > 1 ? std::bit_width(count_ - 1) : 0;
    const std::uint32_t leaves = 1u << pointDepth_;
    bind();
    keys_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS);
    values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
    pointKeys_.set("clusterCount", count_);
    pointKeys_.set("paddedCount", leaves);
    pointKeys_.set("useSamples", useSamples ? 1 : 0);
    pointKeys_.set("boundsLo", lo_);
    pointKeys_.set("boundsExtent", extent_);
    dispatchCompute(pointKeys_, {int(leaves), 1, 1}, {64, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    sort_.sort(keys_, values_, keysTmp_, valuesTmp_, leaves, 32, counters, kCounterScratch);
    bind();
    keys_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS);
    values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
    bindPointTree(pointLeaves_);
    pointLeaves_.set("useSamples", useSamples ? 1 : 0);
    dispatchCompute(pointLeaves_, {int(leaves), 1, 1}, {64, 1, 1});
    bindPointTree(pointReduce_);
    for (int level = pointDepth_ - 1; level >= 0; --level) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        pointReduce_.set("level", level);
        dispatchCompute(pointReduce_, {1 << level, 1, 1}, {64, 1, 1});
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void ShadingClusters::assign(bool onlyClassify)
{
    bind();
    clusterOfPixel_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_OF_PIXEL);
    keys_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS);
    values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
    setCommon(assign_);
    bindPointTree(assign_);
    assign_.set("clusterCount", count_);
    assign_.set("bruteForce", settings_.bruteForce ? 1 : 0);
    assign_.set("onlyClassify", onlyClassify ? 1 : 0);
    assign_.set("errorSlack", settings_.errorSlack);
    dispatchCompute(assign_, {width_, height_, 1}, {8, 8, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void ShadingClusters::sortByCluster(Buffer& counters)
{
    const auto pixels = std::uint32_t(width_ * height_);
    sort_.sort(keys_, values_, keysTmp_, valuesTmp_, pixels, std::bit_width(count_ + 1), counters, kCounterScratch);
}

void ShadingClusters::runSegments()
{
    bind();
    keys_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS);
    segments_.set("pixelCount", std::uint32_t(width_ * height_));
    segments_.set("clusterCount", count_);
    dispatchCompute(segments_, {width_ * height_, 1, 1}, {64, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void ShadingClusters::cluster(const Frame& frame, float sceneSize, Buffer& counters, PassTimers& timers)
{
    auto t = timers.scope("kmeans");
    allocate(frame.width(), frame.height());
    const core::Bounds& b = frame.gpuScene().bounds();
    const glm::vec3 extent = b.empty() ? glm::vec3(1.0f) : b.extent();
    lo_ = (b.empty() ? glm::vec3(0.0f) : b.lo) - 1e-3f * sceneSize;
    extent_ = glm::max(extent + 2e-3f * sceneSize, glm::vec3(1e-30f));
    alpha_ = settings_.alpha / std::max(sceneSize, 1e-30f);
    frame.bindGBuffer();
    const auto k = std::uint32_t(std::max(settings_.clusters, 1));
    if (settings_.everyPixel) {
        bind();
        clusterOfPixel_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_OF_PIXEL);
        setCommon(perPixel_);
        dispatchCompute(perPixel_, {width_, height_, 1}, {8, 8, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        count_ = std::uint32_t(width_ * height_);
        nonEmpty_ = count_;
        seeds_ = survivors_ = 0;
        return;
    }

    survivors_ = 0;
    if (settings_.temporal && havePrevious_ && count_ > 0) {
        // Temporal reuse: the previous centres, fixed, take the points within their largest error.
        buildPointTree(false, counters);
        assign(true);
        sortByCluster(counters);
        runSegments();
        bind();
        marksBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_SCAN);
        marks_.set("clusterCount", count_);
        dispatchCompute(marks_, {int(count_), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        scan_.run(marksBuffer_, count_, counters, kCounterFirst);
        std::swap(clusters_, spare_);
        if (!clusters_) clusters_ = Buffer("photon.clusters", std::size_t(k) * sizeof(GpuCluster));
        spare_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_SEEDS);
        bind();
        marksBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_SCAN);
        survivorsProgram_.set("clusterCount", count_);
        dispatchCompute(survivorsProgram_, {int(count_), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        counters.download(kCounterFirst * 4, 4, &survivors_);
        buildQuadtree(true);
    } else {
        buildQuadtree(false);
    }
    placeSeeds(survivors_, k > survivors_ ? k - survivors_ : 0, counters);
    count_ = survivors_ + seeds_;
    if (count_ == 0) {
        nonEmpty_ = 0;
        havePrevious_ = false;
        return;
    }

    for (int it = 0; it < settings_.iterations; ++it) {
        buildPointTree(false, counters);
        assign(false);
        sortByCluster(counters);
        runSegments();
        bind();
        values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
        setCommon(update_);
        update_.set("clusterCount", count_);
        update_.set("fixedClusters", survivors_);
        dispatchCompute(update_, {int(count_), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    buildPointTree(false, counters);
    assign(false);
    sortByCluster(counters);
    runSegments();
    const std::uint32_t zero = 0;
    counters.update(kCounterClusters * 4, 4, &zero);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    bind();
    values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
    setCommon(sample_);
    sample_.set("clusterCount", count_);
    dispatchCompute(sample_, {int(count_), 1, 1}, {64, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    counters.download(kCounterClusters * 4, 4, &nonEmpty_);
    havePrevious_ = true;
}

std::vector<GpuCluster> ShadingClusters::download() const
{
    std::vector<GpuCluster> c = clusters_.download<GpuCluster>();
    c.resize(count_);
    return c;
}

std::vector<std::uint32_t> ShadingClusters::downloadClusterOfPixel() const
{
    std::vector<std::uint32_t> c = clusterOfPixel_.download<std::uint32_t>();
    c.resize(std::size_t(width_) * std::size_t(height_));
    return c;
}

std::size_t ShadingClusters::bytes() const
{
    return quad_.bytes() + seedsBuffer_.bytes() + clusterOfPixel_.bytes() + clusters_.bytes() + spare_.bytes() +
           keys_.bytes() + values_.bytes() + keysTmp_.bytes() + valuesTmp_.bytes() + pointTree_.bytes() +
           marksBuffer_.bytes() + sort_.bytes();
}

} // namespace bounce::gl
