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

// The work the kernels share (per-scope work, kernelWork): gbufferSurface (common/gbuffer.glsl) fetches
// one RG32UI texel, rebuilds the position from the eye depth and decodes the octahedral normal;
// clusterError is Eq. 2. The kernels' buffers by their std430 sizes.
constexpr double kSurfaceFlops = 40, kSurfaceBytes = 8, kErrorFlops = 26;
constexpr double kClusterBytes = sizeof(GpuCluster), kQuadNodeBytes = sizeof(GpuQuadNode),
                 kPointNodeBytes = sizeof(GpuPointNode);

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
      survivorOfPixel_(compute("kmeansSurvivorOfPixel", "kmeans_survivor_of_pixel.comp")),
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
    survivorOfPixelBuffer_ = Buffer("photon.survivorOfPixel", pixels * 4);
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

void ShadingClusters::buildQuadtree(bool onlyUnclassified, PassTimers::Scope& t)
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
    // quad_leaves.comp per pixel of the padded square: its surface (and its previous cluster) read, its
    // node written. Per level above: quad_reduce.comp per node, four children read (the level's offset
    // summed for each index) and the node written; quad_error.comp per node, the node read and eps_q
    // written, per member pixel its surface and Eq. 2 error (a bound: every pixel a member), and for nodes
    // of a work group the group's sum.
    const double pixels = double(width_) * height_, classify = onlyUnclassified ? 4 : 0;
    t.addWork(kernelWork(
        double(quadSize_) * quadSize_,
        {.flops = kSurfaceFlops, .fetches = 1, .bytesRead = kSurfaceBytes + classify, .bytesWritten = kQuadNodeBytes}));
    for (int level = 1; level <= quadLevels_; ++level) {
        const double nodes = double(quadSize_ >> level) * (quadSize_ >> level);
        t.addWork(kernelWork(
            nodes, {.flops = 28 + 15.0 * level, .bytesRead = 4 * kQuadNodeBytes, .bytesWritten = kQuadNodeBytes}));
        t.addWork(kernelWork(nodes, {.flops = 20 + 3.0 * level, .bytesRead = kQuadNodeBytes, .bytesWritten = 4}));
        t.addWork(kernelWork(
            pixels, {.flops = kSurfaceFlops + kErrorFlops, .fetches = 1, .bytesRead = kSurfaceBytes + classify}));
        if ((1 << level) > kQuadGroupSpan) t.addWork(kernelWork(nodes * kQuadGroup, {.flops = 16}));
    }
}

void ShadingClusters::placeSeeds(std::uint32_t first, std::uint32_t count, Buffer& counters, PassTimers::Scope& t)
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
    // seed_distribute.comp per node, top-down: its seeds read and, above the pixels, its four children
    // read, its seeds shared out among them (the water-filling) and written; seed_write.comp per pixel: its
    // seeds read, and per seed placed the pixel's surface read and a cluster written.
    for (int level = quadLevels_; level >= 0; --level) {
        const double nodes = double(quadSize_ >> level) * (quadSize_ >> level);
        if (level == 0)
            t.addWork(kernelWork(nodes, {.flops = 4, .bytesRead = 8}));
        else
            t.addWork(kernelWork(
                nodes, {.flops = 100 + 15.0 * level, .bytesRead = 8 + 4 * kQuadNodeBytes, .bytesWritten = 4 * 8}));
    }
    t.addWork(kernelWork(double(width_) * height_, {.flops = 4, .bytesRead = 8}));
    t.addWork(kernelWork(
        seeds_, {.flops = kSurfaceFlops, .fetches = 1, .bytesRead = kSurfaceBytes, .bytesWritten = kClusterBytes}));
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

void ShadingClusters::addPointTreeWork(PassTimers::Scope& t) const
{
    // point_keys.comp per leaf: its cluster read, its Morton code, key and value written; the radix sort of
    // the keys; point_leaves.comp per leaf: key, value, the point and its normal read, the leaf written;
    // point_reduce.comp per node above: two children (and R_j of leaves' clusters) read, the boxes merged
    // and packed, the node written.
    const double leaves = double(1u << pointDepth_);
    t.addWork(kernelWork(leaves, {.flops = 40, .bytesRead = kClusterBytes, .bytesWritten = 8}));
    t.addWork(sort_.work(1u << pointDepth_, 32));
    t.addWork(kernelWork(leaves, {.flops = 12, .bytesRead = 8 + 32, .bytesWritten = kPointNodeBytes}));
    t.addWork(
        kernelWork(leaves - 1, {.flops = 40, .bytesRead = 2 * kPointNodeBytes + 8, .bytesWritten = kPointNodeBytes}));
}

std::uint32_t ShadingClusters::assign(bool onlyClassify, bool countMoves, Buffer& counters, PassTimers::Scope& t)
{
    if (countMoves) {
        const std::uint32_t zero = 0;
        counters.update(kCounterFirst * 4, 4, &zero);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    bind();
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
    clusterOfPixel_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_OF_PIXEL);
    keys_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS);
    values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
    setCommon(assign_);
    bindPointTree(assign_);
    assign_.set("clusterCount", count_);
    assign_.set("bruteForce", settings_.bruteForce ? 1 : 0);
    assign_.set("onlyClassify", onlyClassify ? 1 : 0);
    assign_.set("errorSlack", settings_.errorSlack);
    assign_.set("countMoves", countMoves ? 1 : 0);
    // The survivors' shortcut (kmeans_assign.comp): tries the new clusters at every kept pixel, so only
    // while they are few.
    const bool shortcut = !onlyClassify && settings_.temporal && survivors_ > 0 && count_ - survivors_ <= kShortcutNew;
    assign_.set("fixedClusters", shortcut ? survivors_ : 0u);
    survivorOfPixelBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_SEEDS);
    dispatchCompute(assign_, {width_, height_, 1}, {8, 8, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t moved = 0;
    if (countMoves) counters.download(kCounterFirst * 4, 4, &moved);
    // kmeans_assign.comp per pixel: its surface and previous cluster read and Eq. 2 to that centre, then
    // the walk of the tree of centres, taken as two nodes per level (a box bound each) and two leaves'
    // centres (an estimate: the walk's length is known only on the GPU; bruteForce: every centre; the
    // survivors' shortcut: its survivor and the new clusters); cluster, key and value written.
    const bool walk = !settings_.bruteForce && !shortcut;
    const double boxes = walk ? 2.0 * pointDepth_ : 0.0, centres = 1.0 + (settings_.bruteForce ? double(count_)
                                                                          : shortcut ? 1.0 + double(count_ - survivors_)
                                                                                     : 2.0);
    t.addWork(
        kernelWork(double(width_) * height_, {.flops = kSurfaceFlops + 35 * boxes + kErrorFlops * centres,
                                              .fetches = 1,
                                              .bytesRead = kSurfaceBytes + 4 + kPointNodeBytes * boxes + 32 * centres,
                                              .bytesWritten = 12}));
    return moved;
}

void ShadingClusters::sortByCluster(Buffer& counters, PassTimers::Scope& t)
{
    const auto pixels = std::uint32_t(width_ * height_);
    sort_.sort(keys_, values_, keysTmp_, valuesTmp_, pixels, std::bit_width(count_ + 1), counters, kCounterScratch);
    t.addWork(sort_.work(pixels, std::bit_width(count_ + 1)));
}

void ShadingClusters::runSegments(PassTimers::Scope& t)
{
    bind();
    keys_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS);
    segments_.set("pixelCount", std::uint32_t(width_ * height_));
    segments_.set("clusterCount", count_);
    dispatchCompute(segments_, {width_ * height_, 1, 1}, {64, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    // kmeans_segments.comp per sorted pixel: its key and its neighbours' read; each segment's ends written.
    t.addWork(kernelWork(double(width_) * height_, {.flops = 4, .bytesRead = 12}));
    t.addWork(kernelWork(count_, {.bytesWritten = 8}));
}

void ShadingClusters::cluster(const Frame& frame, float sceneSize, Buffer& counters, PassTimers& timers)
{
    // No work is common to all its kernels' invocations: each step adds its kernels' work, from the counts
    // known here (pixels, clusters, seeds, the trees' depths).
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
        // clusters_per_pixel.comp per pixel: its surface read, its cluster and cluster index written.
        t.addWork(kernelWork(
            double(width_) * height_,
            {.flops = kSurfaceFlops + 4, .fetches = 1, .bytesRead = kSurfaceBytes, .bytesWritten = kClusterBytes + 4}));
        count_ = std::uint32_t(width_ * height_);
        nonEmpty_ = count_;
        seeds_ = survivors_ = 0;
        return;
    }

    survivors_ = 0;
    if (settings_.temporal && havePrevious_ && count_ > 0) {
        // Temporal reuse: the previous centres, fixed, take the points within their largest error.
        buildPointTree(false, counters);
        addPointTreeWork(t);
        assign(true, false, counters, t);
        sortByCluster(counters, t);
        runSegments(t);
        bind();
        marksBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
        marks_.set("clusterCount", count_);
        dispatchCompute(marks_, {int(count_), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        scan_.run(marksBuffer_, count_, counters, kCounterFirst);
        std::swap(clusters_, spare_);
        if (!clusters_) clusters_ = Buffer("photon.clusters", std::size_t(k) * sizeof(GpuCluster));
        spare_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_SEEDS);
        bind();
        marksBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
        survivorsProgram_.set("clusterCount", count_);
        dispatchCompute(survivorsProgram_, {int(count_), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        counters.download(kCounterFirst * 4, 4, &survivors_);
        bind();
        clusterOfPixel_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_OF_PIXEL);
        marksBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
        survivorOfPixelBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_SEEDS);
        const auto pixelCount = std::uint32_t(width_ * height_);
        survivorOfPixel_.set("pixelCount", pixelCount);
        survivorOfPixel_.set("previousCount", count_);
        dispatchCompute(survivorOfPixel_, {int(pixelCount), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        // kmeans_marks.comp per previous cluster: its members' range read, its mark written; the scan of the
        // marks; kmeans_survivors.comp per previous cluster: it and its position read, a survivor written.
        t.addWork(kernelWork(count_, {.flops = 1, .bytesRead = 16, .bytesWritten = 4}));
        t.addWork(GpuScan::work(count_));
        t.addWork(kernelWork(count_, {.bytesRead = kClusterBytes + 4}));
        t.addWork(kernelWork(survivors_, {.bytesWritten = kClusterBytes}));
        // kmeans_survivor_of_pixel.comp per pixel: its cluster and that cluster's position read, one word written.
        t.addWork(kernelWork(double(width_) * height_, {.bytesRead = 8, .bytesWritten = 4}));
        buildQuadtree(true, t);
    } else {
        buildQuadtree(false, t);
    }
    placeSeeds(survivors_, k > survivors_ ? k - survivors_ : 0, counters, t);
    count_ = survivors_ + seeds_;
    if (count_ == 0) {
        nonEmpty_ = 0;
        havePrevious_ = false;
        return;
    }

    const double pixels = double(width_) * height_;
    // "until either the clustering converges or a maximum number of iterations has been reached": from the
    // second iteration on, the pixels that changed cluster are counted (the first compares with another
    // frame's or the seeds' clusters), and an iteration that moves at most `tolerance` of them ends k-means
    // with its assignment. With tolerance 0 that is exact: an assignment that moves no pixel gives the
    // centres the last update made, so every later iteration and the final assignment would repeat it.
    const auto movesAllowed = std::uint32_t(double(settings_.tolerance) * pixels);
    bool converged = false;
    iterationsRun_ = 0;
    for (int it = 0; it < settings_.iterations; ++it) {
        buildPointTree(false, counters);
        addPointTreeWork(t);
        const std::uint32_t moved = assign(false, it > 0, counters, t);
        converged = it > 0 && moved <= movesAllowed;
        sortByCluster(counters, t);
        runSegments(t);
        ++iterationsRun_;
        if (converged) break;
        bind();
        values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
        setCommon(update_);
        update_.set("clusterCount", count_);
        update_.set("fixedClusters", survivors_);
        dispatchCompute(update_, {int(count_), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        // kmeans_update.comp per cluster: its record read, its centre, normal and members written; per
        // member (a bound: every pixel) its index and surface read and summed.
        t.addWork(kernelWork(count_, {.flops = 15, .bytesRead = kClusterBytes, .bytesWritten = 48}));
        t.addWork(kernelWork(pixels, {.flops = kSurfaceFlops + 10, .fetches = 1, .bytesRead = 4 + kSurfaceBytes}));
    }
    if (!converged) {
        buildPointTree(false, counters);
        addPointTreeWork(t);
        assign(false, false, counters, t);
        sortByCluster(counters, t);
        runSegments(t);
    }
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
    // kmeans_sample.comp per cluster: its record and its sample's surface read, the record and the counter
    // written; per member (a bound: every pixel) its index and surface read and its Eq. 2 error.
    t.addWork(kernelWork(
        count_,
        {.flops = kSurfaceFlops + 5, .fetches = 1, .bytesRead = kClusterBytes + kSurfaceBytes, .bytesWritten = 60}));
    t.addWork(
        kernelWork(pixels, {.flops = kSurfaceFlops + kErrorFlops + 6, .fetches = 1, .bytesRead = 4 + kSurfaceBytes}));
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
           marksBuffer_.bytes() + survivorOfPixelBuffer_.bytes() + sort_.bytes();
}

} // namespace bounce::gl
