#include "gl/technique/photon/photon_tracer.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/photon/bindings.h"

namespace bounce::gl {

namespace {

double luminance(const glm::vec3& c)
{
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

} // namespace

glm::vec3 emittedPower(const LightSource& light, float directionalRadius)
{
    constexpr double pi = 3.14159265358979323846;
    switch (light.type) {
    case kLightPoint: return float(4.0 * pi) * light.intensity;
    case kLightSpot: {
        // The integral over the cone of glTF's falloff: 1 inside the inner cone, t^2 between the cones
        // (t linear in the cosine): 2 pi ((1 - cos inner) + (cos inner - cos outer) / 3).
        const double co = light.cosOuter, ci = std::max(light.cosInner, light.cosOuter);
        return float(2.0 * pi * ((1.0 - ci) + (ci - co) / 3.0)) * light.intensity;
    }
    case kLightDirectional: return float(pi * double(directionalRadius) * directionalRadius) * light.intensity;
    default: {
        const glm::vec3 c = glm::cross(light.triangle[1] - light.triangle[0], light.triangle[2] - light.triangle[0]);
        return float(pi * 0.5 * double(glm::length(c))) * light.intensity;
    }
    }
}

PhotonTracer::PhotonTracer(const PhotonTracerSettings& settings)
    : settings_(settings),
      trace_(Program::compute("photon.trace", "technique/photon/photon_trace.comp")),
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

void PhotonTracer::buildEmitters(const Frame& frame)
{
    const core::Bounds& b = frame.gpuScene().bounds();
    const glm::vec3 extent = b.empty() ? glm::vec3(1.0f) : b.extent();
    size_ = std::max(glm::length(extent), 1e-30f);
    lo_ = (b.empty() ? glm::vec3(0.0f) : b.lo) - 1e-3f * size_;
    extent_ = glm::max(extent + 2e-3f * size_, glm::vec3(1e-30f));
    const float radius = 0.5f * size_ * 1.01f;

    const std::vector<LightSource>& lights = frame.gpuScene().lights();
    std::vector<glm::vec3> power;
    std::vector<double> weight;
    for (const LightSource& l : lights) {
        power.push_back(emittedPower(l, radius));
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
    std::uint32_t first = 0;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        if (count[i] == 0) continue; // a light of no power, or fewer photons than lights
        const LightSource& l = lights[i];
        PhotonEmitter e{};
        e.positionType = glm::vec4(l.position, float(l.type));
        e.directionCos = glm::vec4(l.direction, l.cosOuter);
        e.powerCosInner = glm::vec4(power[i] / float(count[i]), l.cosInner);
        if (l.type == kLightDirectional) {
            const glm::vec3 centre = b.empty() ? glm::vec3(0.0f) : b.centre();
            e.positionType = glm::vec4(centre - l.direction * (2.0f * radius), float(l.type));
            e.v0 = glm::vec4(0.0f, 0.0f, 0.0f, radius);
        }
        if (l.type == kLightArea) {
            e.v0 = glm::vec4(l.triangle[0], 0.0f);
            e.v1 = glm::vec4(l.triangle[1], 0.0f);
            e.v2 = glm::vec4(l.triangle[2], 0.0f);
        }
        e.range = glm::uvec4(first, count[i], 0, 0);
        first += count[i];
        emitters_.push_back(e);
    }
    if (emitters_.empty()) emitters_.push_back(PhotonEmitter{}); // an SSBO may not be empty
    emitterBuffer_ = Buffer::fromVector("photon.emitters", emitters_);
    if (first == 0) emitters_.clear();
}

void PhotonTracer::trace(const Frame& frame, const RayCaster& caster, Buffer& counters, PassTimers& timers)
{
    const auto paths = std::uint32_t(std::max(settings_.photons, 0));
    {
        auto t = timers.scope("photon-trace");
        buildEmitters(frame);
        for (;;) {
            const std::uint32_t zero[3] = {0, 0, 0};
            counters.update(0, sizeof zero, zero);
            frame.bindSceneData();
            caster.bind();
            emitterBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_EMITTERS);
            counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
            staging_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_STAGING);
            pathCounts_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_PATHS);
            emitted_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_EMITTED);
            trace_.set("pathCount", paths);
            trace_.set("emitterCount", int(emitters_.size()));
            trace_.set("capacity", unsigned(capacity_));
            trace_.set("maxBounces", settings_.maxBounces);
            trace_.set("russianRoulette", settings_.russianRoulette ? 1 : 0);
            trace_.set("rayEpsilon", 1e-5f * size_);
            trace_.set("seed", settings_.seed);
            if (paths > 0) dispatchCompute(trace_, {int(paths), 1, 1}, {64, 1, 1});
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
            std::uint32_t staged = 0;
            counters.download(kCounterStaged * 4, 4, &staged);
            stored_ = staged;
            if (staged <= std::uint32_t(capacity_)) break;
            // Out of space: double until it fits (section 5's dynamic arrays), and trace again.
            int grown = capacity_;
            while (std::uint32_t(grown) < staged) grown *= 2;
            allocate(grown);
            ++grown_;
        }
    }
    auto t = timers.scope("photon-sort");
    if (paths > 0) scan_.run(pathCounts_, paths, counters, kCounterStored);
    if (stored_ == 0) return;
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
    return emitterBuffer_.bytes() + staging_.bytes() + sorted_.bytes() + pathCounts_.bytes() + emitted_.bytes() +
           keys_.bytes() + values_.bytes() + keysTmp_.bytes() + valuesTmp_.bytes() + sort_.bytes();
}

} // namespace bounce::gl
