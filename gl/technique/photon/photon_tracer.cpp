#include "gl/technique/photon/photon_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <thread>
#include <vector>

#include "gl/context/context.h"
#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/photon/bindings.h"

namespace bounce::gl {

namespace {

constexpr double kPiDouble = 3.14159265358979323846;

double luminance(const glm::vec3& c)
{
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

// What a light's photons carry together before a spot's falloff: photon_trace.comp draws a spot's
// directions uniformly in its outer cone and weights each photon by glTF's falloff, so their base is the
// intensity times the outer cone's solid angle, not the light's power (which holds the falloff already:
// with both, a soft spot's photons carried its power times the falloff's mean over the cone, 0.63 for
// cones of 0.4 and 0.6 rad). The same for every other kind of light.
glm::vec3 powerBeforeFalloff(const LightSource& light, const glm::vec3& power)
{
    if (light.type != kLightSpot) return power;
    return float(2.0 * kPiDouble * (1.0 - double(light.cosOuter))) * light.intensity;
}

} // namespace

void orderAsKdTree(std::vector<GpuPhoton>& photons)
{
    // The splits move 16-byte items (position, photon index), not the 64-byte photons, which are permuted
    // once at the end. A NaN coordinate is ordered as +infinity: nth_element needs a strict weak order,
    // which `<` on NaN is not.
    struct Item {
        glm::vec3 p;
        std::uint32_t photon;
    };
    const std::uint64_t n = photons.size();
    std::vector<Item> items(photons.size());
    for (std::size_t i = 0; i < photons.size(); ++i) {
        glm::vec3 p(photons[i].positionPath);
        for (int c = 0; c < 3; ++c)
            if (std::isnan(p[c])) p[c] = std::numeric_limits<float>::infinity();
        items[i] = {p, std::uint32_t(i)};
    }
    // Node k of level l holds [floor(k n / 2^l), floor((k + 1) n / 2^l)) (photon_tree.glsl's nodeRange); its
    // children meet at floor((2k + 1) n / 2^(l + 1)), where the median along the box's longest side goes.
    const auto split = [&](auto&& self, std::uint32_t lo, std::uint32_t hi, std::uint64_t k, int l) -> void {
        if (hi - lo <= 1 || l >= 31) return;
        glm::vec3 a(std::numeric_limits<float>::infinity()), b(-std::numeric_limits<float>::infinity());
        for (std::uint32_t i = lo; i < hi; ++i) {
            a = glm::min(a, items[i].p);
            b = glm::max(b, items[i].p);
        }
        const glm::vec3 side = b - a;
        const int axis = side.x >= side.y && side.x >= side.z ? 0 : (side.y >= side.z ? 1 : 2);
        const auto mid = std::uint32_t(((2 * k + 1) * n) >> (l + 1));
        const auto first = items.begin() + lo, nth = items.begin() + mid, last = items.begin() + hi;
        if (axis == 0)
            std::nth_element(first, nth, last, [](const Item& x, const Item& y) { return x.p.x < y.p.x; });
        else if (axis == 1)
            std::nth_element(first, nth, last, [](const Item& x, const Item& y) { return x.p.y < y.p.y; });
        else
            std::nth_element(first, nth, last, [](const Item& x, const Item& y) { return x.p.z < y.p.z; });
        // The two halves are independent: below the root, the lower one on a second thread (the same
        // order either way).
        if (l == 0 && mid - lo >= 4096) {
            std::thread lower([&] { self(self, lo, mid, 2 * k, l + 1); });
            self(self, mid, hi, 2 * k + 1, l + 1);
            lower.join();
        } else {
            self(self, lo, mid, 2 * k, l + 1);
            self(self, mid, hi, 2 * k + 1, l + 1);
        }
    };
    split(split, 0, std::uint32_t(n), 0, 0);
    std::vector<GpuPhoton> ordered(photons.size());
    for (std::size_t i = 0; i < items.size(); ++i) ordered[i] = photons[items[i].photon];
    photons.swap(ordered);
}

glm::vec3 emittedPower(const LightSource& light, float directionalArea)
{
    switch (light.type) {
    case kLightPoint: return float(4.0 * kPiDouble) * light.intensity;
    case kLightSpot: {
        // The integral over the cone of glTF's falloff: 1 inside the inner cone, t^2 between the cones
        // (t linear in the cosine): 2 pi ((1 - cos inner) + (cos inner - cos outer) / 3).
        const double co = light.cosOuter, ci = std::max(light.cosInner, light.cosOuter);
        return float(2.0 * kPiDouble * ((1.0 - ci) + (ci - co) / 3.0)) * light.intensity;
    }
    case kLightDirectional: return directionalArea * light.intensity;
    default: {
        const glm::vec3 c = glm::cross(light.triangle[1] - light.triangle[0], light.triangle[2] - light.triangle[0]);
        return float(kPiDouble * 0.5 * double(glm::length(c))) * light.intensity;
    }
    }
}

PassCost bvhWalkWork(const core::Bvh& bvh, double walks)
{
    // raycast.glsl per walk: the ray's shear and inverse direction (six divisions), about 2 x depth boxes
    // (32 bytes, 24 flops each) and two leaves of kMaxLeafSize triangles (48 bytes, 60 flops each), and the
    // hit's division. A division is one flop where the driver divides as IEEE 754 does (llvmpipe), else
    // about 85 (rayDivide's correction).
    const double division = softwareRasterizer() ? 1.0 : 85.0;
    const double boxes = 2.0 * std::max(bvh.depth(), 1), triangles = 2.0 * core::Bvh::kMaxLeafSize;
    PassCost w;
    w.flopsFixed = walks * (20 + 7 * division + 24 * boxes + 60 * triangles);
    w.bytesFixed = walks * (sizeof(core::BvhNode) * boxes + sizeof(core::BvhTriangle) * triangles);
    return w;
}

PhotonTracer::PhotonTracer(const PhotonTracerSettings& settings)
    : settings_(settings),
      place_(Program::compute("photon.place", "technique/photon/photon_place.comp")),
      permute_(Program::compute("photon.permute", "technique/photon/photon_permute.comp"))
{
    const std::size_t n = std::size_t(std::max(settings_.photons, 1));
    pathCounts_ = Buffer("photon.pathCounts", n * 4);
    emitted_ = Buffer("photon.emitted", n * 16);
    // The paper's dynamic arrays (section 5): start at twice the paths, double when a frame overflows.
    allocate(int(std::min<std::size_t>(2 * n, 1u << 26)));
}

void PhotonTracer::allocate(int capacity)
{
    capacity_ = std::max(capacity, 1);
    const std::size_t c = std::size_t(capacity_);
    staging_ = Buffer("photon.staging", c * sizeof(GpuPhoton));
    sorted_ = Buffer("photon.photons", c * sizeof(GpuPhoton));
    keys_ = Buffer("photon.sortKeys", c * 4);
    values_ = Buffer("photon.sortValues", c * 4);
    keysTmp_ = Buffer("photon.sortKeysTmp", c * 4);
    valuesTmp_ = Buffer("photon.sortValuesTmp", c * 4);
}

std::vector<std::uint32_t> ProjectionMap::entries() const
{
    std::vector<std::uint32_t> list;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const std::uint32_t k = copies.empty() ? 1u : copies[i];
        list.insert(list.end(), k, cells[i] | (k << 16));
    }
    return list;
}

std::vector<std::uint32_t> guidedCopies(const std::vector<double>& storedPerCell)
{
    std::vector<std::uint32_t> copies(storedPerCell.size(), 1u);
    const double total = std::accumulate(storedPerCell.begin(), storedPerCell.end(), 0.0);
    if (!(total > 0.0)) return copies;
    const double mean = total / double(storedPerCell.size());
    for (std::size_t i = 0; i < copies.size(); ++i)
        copies[i] = std::uint32_t(
            std::clamp(std::lround(kCopiesAtMean * storedPerCell[i] / mean), 1L, long(ProjectionMap::kMaxCopies)));
    return copies;
}

ProjectionMap PhotonTracer::project(const Frame& frame, const RayCaster& caster, glm::vec3 direction, float radius)
{
    // 64^2 cells of 4^2 probes: a cell is 1/32 of the scene's bounding radius across, and the marks are
    // widened by a cell so that an edge the probes pass between still sends photons.
    constexpr int kGrid = 64;
    constexpr unsigned kProbes = 4;
    static_assert(kGrid * kGrid <= 65536, "a cell's index must fit an emission entry's low 16 bits");
    const core::Bounds& b = frame.gpuScene().bounds();
    const glm::vec3 centre = b.empty() ? glm::vec3(0.0f) : b.centre();
    ProjectionMap map;
    map.direction = direction;
    map.gridSize = kGrid;
    map.cellSide = 2.0f * radius / float(kGrid);
    const glm::vec3 helper = std::abs(direction.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    map.axisU = glm::normalize(glm::cross(direction, helper));
    map.axisV = glm::cross(direction, map.axisU);
    map.corner = centre - direction * (2.0f * radius) - radius * (map.axisU + map.axisV);
    std::vector<std::uint32_t> marks(kGrid * kGrid, 1u);
    if (settings_.projectionMap) {
        // Probes pass through the holes of alpha masks, as the photons do.
        if (!project_)
            project_ = Program::compute("photon.project", "technique/photon/photon_project.comp", caster.defines());
        Buffer buffer("photon.projectionMarks", marks.size() * 4);
        frame.bindSceneData();
        caster.bind();
        buffer.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
        project_.set("corner", map.corner);
        project_.set("axisU", map.axisU);
        project_.set("axisV", map.axisV);
        project_.set("direction", direction);
        project_.set("cellSide", map.cellSide);
        project_.set("gridSize", unsigned(kGrid));
        project_.set("probesPerSide", kProbes);
        dispatchCompute(project_, {kGrid * kGrid, 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        marks = buffer.download<std::uint32_t>();
        marks.resize(kGrid * kGrid);
    }
    for (int y = 0; y < kGrid; ++y)
        for (int x = 0; x < kGrid; ++x) {
            bool near = false;
            for (int dy = -1; dy <= 1 && !near; ++dy)
                for (int dx = -1; dx <= 1 && !near; ++dx) {
                    const int u = x + dx, v = y + dy;
                    near = u >= 0 && v >= 0 && u < kGrid && v < kGrid && marks[std::size_t(v * kGrid + u)] != 0;
                }
            if (near) map.cells.push_back(std::uint32_t(y * kGrid + x));
        }
    return map;
}

void PhotonTracer::buildEmitters(const Frame& frame, const RayCaster& caster)
{
    const core::Bounds& b = frame.gpuScene().bounds();
    const glm::vec3 extent = b.empty() ? glm::vec3(1.0f) : b.extent();
    size_ = std::max(glm::length(extent), 1e-30f);
    lo_ = (b.empty() ? glm::vec3(0.0f) : b.lo) - 1e-3f * size_;
    extent_ = glm::max(extent + 2e-3f * size_, glm::vec3(1e-30f));
    const float radius = 0.5f * size_ * 1.01f;

    const std::vector<LightSource>& lights = frame.gpuScene().lights();
    // Projection maps of the directional lights, kept while the light, the scene's bounds and its geometry hold.
    if (frame.version().scene != projectionsScene_) projections_.clear();
    projectionsScene_ = frame.version().scene;
    std::vector<ProjectionMap> maps;
    for (const LightSource& l : lights) {
        if (l.type != kLightDirectional) continue;
        auto same = std::find_if(projections_.begin(), projections_.end(), [&](const ProjectionMap& m) {
            return m.direction == l.direction && m.cellSide == 2.0f * radius / float(m.gridSize);
        });
        maps.push_back(same != projections_.end() ? *same : project(frame, caster, l.direction, radius));
    }
    projections_ = maps;
    std::vector<std::uint32_t> cells;
    std::vector<glm::vec3> power;
    std::vector<double> weight;
    std::size_t directional = 0;
    for (const LightSource& l : lights) {
        float area = 0.0f;
        if (l.type == kLightDirectional) {
            const ProjectionMap& m = projections_[directional++];
            area = float(m.cells.size()) * m.cellSide * m.cellSide;
        }
        power.push_back(emittedPower(l, area));
        weight.push_back(std::max(0.0, luminance(power.back())));
    }
    // Photons in proportion to luminous power, by largest remainder (so that they sum to the count).
    const double total = std::accumulate(weight.begin(), weight.end(), 0.0);
    const auto n = std::uint32_t(std::max(settings_.photons, 0));
    std::vector<std::uint32_t> count(lights.size(), 0);
    if (total > 0.0 && n > 0) {
        std::vector<std::pair<double, std::size_t>> remainders;
        std::uint32_t given = 0;
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const double share = double(n) * weight[i] / total;
            count[i] = std::uint32_t(std::floor(share));
            given += count[i];
            remainders.push_back({share - std::floor(share), i});
        }
        std::stable_sort(remainders.begin(), remainders.end(), [](auto& a, auto& b) { return a.first > b.first; });
        for (std::size_t k = 0; given < n && k < remainders.size(); ++k, ++given) ++count[remainders[k].second];
    }
    emitters_.clear();
    emitterMaps_.clear();
    std::uint32_t first = 0;
    directional = 0;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const LightSource& l = lights[i];
        const int mapIndex = l.type == kLightDirectional ? int(directional++) : -1;
        const ProjectionMap* map = mapIndex >= 0 ? &projections_[std::size_t(mapIndex)] : nullptr;
        if (count[i] == 0) continue; // a light of no power, or fewer photons than lights
        PhotonEmitter e{};
        e.positionType = glm::vec4(l.position, float(l.type));
        e.directionCos = glm::vec4(l.direction, l.cosOuter);
        e.powerCosInner = glm::vec4(powerBeforeFalloff(l, power[i]) / float(count[i]), l.cosInner);
        if (map) {
            e.positionType = glm::vec4(map->corner, float(l.type));
            e.v0 = glm::vec4(map->axisU, map->cellSide);
            e.v1 = glm::vec4(map->axisV, float(map->gridSize));
            // v2: the emission list's length and first entry, and the power's factor entries / cells (the
            // light's power is spread over the distinct cells; a cell with k copies is picked k times as
            // often, so each of its photons carries that factor over k).
            const std::vector<std::uint32_t> list = map->entries();
            e.v2 =
                glm::vec4(float(list.size()), float(cells.size()), float(list.size()) / float(map->cells.size()), 0.0f);
            cells.insert(cells.end(), list.begin(), list.end());
        }
        if (l.type == kLightArea) {
            e.v0 = glm::vec4(l.triangle[0], 0.0f);
            e.v1 = glm::vec4(l.triangle[1], 0.0f);
            e.v2 = glm::vec4(l.triangle[2], 0.0f);
        }
        e.range = glm::uvec4(first, count[i], 0, 0);
        first += count[i];
        emitters_.push_back(e);
        emitterMaps_.push_back(mapIndex);
    }
    if (emitters_.empty()) emitters_.push_back(PhotonEmitter{}); // an SSBO may not be empty
    if (cells.empty()) cells.push_back(0);
    // Every frame calls this; while the lights hold, the sizes do too and the buffers are rewritten in
    // place (the cells' buffer view kept) rather than made anew.
    Buffer::assign(emitterBuffer_, "photon.emitters", emitters_);
    if (Buffer::assign(cells_, "photon.projectionCells", cells))
        cellTexels_ = Texture::createBufferView("photon.projectionCells", GL_R32UI, cells_);
    if (first == 0) {
        emitters_.clear();
        emitterMaps_.clear();
    }
}

void PhotonTracer::guide()
{
    const std::vector<std::uint32_t> stored = pathCounts_.download<std::uint32_t>();
    for (std::size_t k = 0; k < emitters_.size(); ++k) {
        if (emitterMaps_[k] < 0) continue;
        ProjectionMap& map = projections_[std::size_t(emitterMaps_[k])];
        if (!map.copies.empty() || map.cells.empty()) continue;
        // The cell photon_trace.comp's emit() picked for each path, in the same float arithmetic (one copy
        // of each cell in the pilot's list).
        const PhotonEmitter& e = emitters_[k];
        const auto cells = std::uint32_t(map.cells.size());
        std::vector<double> perCell(cells, 0.0);
        for (std::uint32_t j = 0; j < e.range.y && e.range.x + j < stored.size(); ++j) {
            const float u = (float(j) + 0.5f) / float(e.range.y);
            const auto i = std::min(std::uint32_t(u * float(cells)), cells - 1u);
            perCell[i] += double(stored[e.range.x + j]);
        }
        map.copies = guidedCopies(perCell);
    }
}

// photon_trace.comp over every path, traced again with the staging arrays doubled until its photons fit.
void PhotonTracer::dispatchTrace(const Frame& frame, const RayCaster& caster, Buffer& counters, double& surfaces,
                                 double& written)
{
    const auto paths = std::uint32_t(std::max(settings_.photons, 0));
    for (;;) {
        const std::uint32_t zero[3] = {0, 0, 0};
        counters.update(0, sizeof zero, zero);
        frame.bindSceneData();
        caster.bind();
        emitterBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_EMITTERS);
        cellTexels_.bind(UNIT_PHOTON_CELLS);
        counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
        staging_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_STAGING);
        pathCounts_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_PATHS);
        emitted_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_EMITTED);
        trace_.set("pathCount", paths);
        trace_.set("emitterCount", int(emitters_.size()));
        trace_.set("capacity", unsigned(capacity_));
        trace_.set("maxBounces", settings_.maxBounces);
        trace_.set("russianRoulette", settings_.russianRoulette ? 1 : 0);
        trace_.set("firstSurfaceRoulette", settings_.firstSurfaceRoulette);
        trace_.set("rayEpsilon", 1e-5f * size_);
        trace_.set("causticAlpha", causticAlpha(settings_.causticRoughness));
        // Another photon map in every still frame: the frames' mean averages the photons' noise too.
        trace_.set("seed", frame.sampler().hashSeed(settings_.seed));
        if (paths > 0) dispatchCompute(trace_, {int(paths), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        std::uint32_t staged = 0;
        counters.download(kCounterStaged * 4, 4, &staged);
        stored_ = staged;
        surfaces += double(paths) + double(staged);
        written += double(std::min(staged, std::uint32_t(capacity_)));
        if (staged <= std::uint32_t(capacity_)) break;
        // Out of space: double until it fits (section 5's dynamic arrays), and trace again.
        int grown = capacity_;
        while (std::uint32_t(grown) < staged) grown *= 2;
        allocate(grown);
        ++grown_;
    }
}

void PhotonTracer::trace(const Frame& frame, const RayCaster& caster, Buffer& counters, PassTimers& timers)
{
    const auto paths = std::uint32_t(std::max(settings_.photons, 0));
    {
        // photon_trace.comp per path: its emitter found (a binary search) and read, the emission (a
        // Hammersley point, direction and power), the emitted power and the path's photon count written;
        // its surfaces are added below.
        PassCost cost;
        cost.flops = 150;
        cost.bytesRead = sizeof(PhotonEmitter) + 16;
        cost.bytesWritten = 16 + 4;
        auto t = timers.scope("photon-trace", cost);
        buildEmitters(frame, caster);
        const bool directional = !projections_.empty();
        if (!trace_ || traceDirectional_ != directional) {
            // Photons pass through the holes of alpha masks (raycast.glsl, ALPHA_MASK), as the path tracer's
            // rays do (ref/embree_scene.cpp).
            std::vector<Define> defines = caster.defines();
            if (directional) defines.push_back({"DIRECTIONAL_LIGHTS", "1"});
            trace_ = Program::compute("photon.trace", "technique/photon/photon_trace.comp", defines);
            traceDirectional_ = directional;
        }
        double surfaces = 0.0, written = 0.0;
        dispatchTrace(frame, caster, counters, surfaces, written);
        // Guided emission: the first trace of a new projection map is its pilot; its stored photons per
        // cell weight the cells, and the frame's photons are traced again from the weighted list.
        const bool unguided = std::any_of(emitterMaps_.begin(), emitterMaps_.end(),
                                          [&](int m) { return m >= 0 && projections_[std::size_t(m)].copies.empty(); });
        if (settings_.guidedEmission && unguided) {
            guide();
            buildEmitters(frame, caster);
            dispatchTrace(frame, caster, counters, surfaces, written);
        }
        // The surfaces photons reach, taken as every path's first and every stored photon's (an estimate:
        // misses and unstored ends past the first surface are left out): a BVH walk each, then
        // photon_trace.comp reads the triangle's indices, vertices and material (152 bytes; a bilinear
        // base-colour sample where the scene has textures) and samples the BRDF; a stored photon is written
        // with its counter. A directional light's path reads its projection cell; the emitters and cells
        // are uploaded.
        PassCost work = bvhWalkWork(caster.bvh(), surfaces);
        work.flopsFixed += 400 * surfaces;
        work.fetchesFixed = (frame.gpuScene().hasTextures() ? 4 : 0) * surfaces;
        for (const PhotonEmitter& e : emitters_)
            if (int(e.positionType.w) == kLightDirectional) work.fetchesFixed += e.range.y;
        work.bytesFixed +=
            152 * surfaces + (sizeof(GpuPhoton) + 4) * written + double(emitterBuffer_.bytes() + cells_.bytes());
        t.addWork(work);
    }
    // Every count is known here: the scan of the paths' photon counts; photon_place.comp per photon (its
    // path's offset and the photon read, its Hilbert index, the photon, key and value written); the radix
    // sort of the 30-bit keys; photon_permute.comp per photon (its index and the photon read and written).
    auto t = timers.scope("photon-sort");
    if (paths > 0) {
        scan_.run(pathCounts_, paths, counters, kCounterStored);
        t.addWork(GpuScan::work(paths));
    }
    if (stored_ == 0) return;
    t.addWork(kernelWork(stored_, {.flops = 200, .bytesRead = 64 + 4, .bytesWritten = 64 + 4 + 4}));
    t.addWork(sort_.work(stored_, 30));
    t.addWork(kernelWork(stored_, {.bytesRead = 4 + 64, .bytesWritten = 64}));
    staging_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_STAGING);
    pathCounts_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_PATHS);
    sorted_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTONS);
    keys_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS);
    values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
    place_.set("count", stored_);
    place_.set("boundsLo", lo_);
    place_.set("boundsExtent", extent_);
    dispatchCompute(place_, {int(stored_), 1, 1}, {64, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    sort_.sort(keys_, values_, keysTmp_, valuesTmp_, stored_, 30, counters, kCounterScratch);
    sorted_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTONS);
    values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
    staging_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_STAGING);
    permute_.set("count", stored_);
    dispatchCompute(permute_, {int(stored_), 1, 1}, {64, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    std::swap(staging_, sorted_); // sorted_ now holds the photons in Hilbert order
    if (settings_.kdOrder) {
        // Photons to the CPU and back (PhotonTracerSettings::kdOrder; the README's Departures).
        std::vector<GpuPhoton> p(stored_);
        sorted_.download(0, stored_ * sizeof(GpuPhoton), p.data());
        orderAsKdTree(p);
        sorted_.update(0, stored_ * sizeof(GpuPhoton), p.data());
        PassCost copies;
        copies.bytesFixed = 2.0 * sizeof(GpuPhoton) * stored_;
        t.addWork(copies);
    }
}

glm::dvec3 PhotonTracer::emittedTotal() const
{
    const std::vector<glm::vec4> e = emitted_.download<glm::vec4>();
    glm::dvec3 sum(0.0);
    for (std::size_t i = 0; i < std::size_t(std::max(settings_.photons, 0)) && i < e.size(); ++i)
        sum += glm::dvec3(e[i]);
    return sum;
}

std::vector<GpuPhoton> PhotonTracer::downloadPhotons() const
{
    std::vector<GpuPhoton> p = sorted_.download<GpuPhoton>();
    p.resize(stored_);
    return p;
}

std::size_t PhotonTracer::bytes() const
{
    return emitterBuffer_.bytes() + cells_.bytes() + staging_.bytes() + sorted_.bytes() + pathCounts_.bytes() +
           emitted_.bytes() + keys_.bytes() + values_.bytes() + keysTmp_.bytes() + valuesTmp_.bytes() + sort_.bytes();
}

} // namespace bounce::gl
