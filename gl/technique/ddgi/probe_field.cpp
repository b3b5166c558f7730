#include "gl/technique/ddgi/probe_field.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "gl/frame/ray_caster.h"
#include "gl/frame/shader_costs.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/ddgi/bindings.h"

namespace bounce::gl {

namespace {

constexpr int kTraceGroup = 64; // ddgi_trace.comp, ddgi_probe_state.comp

// SplitMix64 (Steele, Lea & Flood 2014): a well-mixed 64-bit word from a counter.
std::uint64_t splitMix64(std::uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

double unit(std::uint64_t bits)
{
    return double(bits >> 11) * (1.0 / 9007199254740992.0);
}

std::vector<Define> traceDefines(const Frame& frame, const ProbeFieldSettings& s)
{
    std::vector<Define> d = frame.gpuScene().alphaMaskDefines();
    if (!frame.scene().hasGlossy()) d.push_back({"SCENE_DIFFUSE_ONLY", "1"});
    if (s.bounces) d.push_back({"BOUNCES", "1"});
    return d;
}

std::vector<Define> stateDefines(const ProbeFieldSettings& s)
{
    std::vector<Define> d;
    if (s.relocation) d.push_back({"RELOCATION", "1"});
    if (s.classification) d.push_back({"CLASSIFICATION", "1"});
    return d;
}

} // namespace

ProbeGrid probeGridFor(const core::Bounds& bounds, int budget)
{
    const glm::vec3 lo = bounds.empty() ? glm::vec3(-0.5f) : bounds.lo;
    glm::vec3 extent = bounds.extent();
    float longest = std::max(extent.x, std::max(extent.y, extent.z));
    if (!(longest > 0.0f) || !std::isfinite(longest)) {
        longest = 1.0f;
        extent = glm::vec3(1.0f);
    }
    extent = glm::max(extent, glm::vec3(1e-3f * longest));
    // The counts at cell size h: the sides over h, rounded, at least 2. The smallest h whose grid fits the
    // budget, by bisection between the longest side (2 x 2 x 2 probes) and a size no budget allows.
    const auto countsAt = [&](double h) {
        glm::ivec3 c;
        for (int a = 0; a < 3; ++a) c[a] = std::max(2, int(std::lround(double(extent[a]) / h)));
        return c;
    };
    const auto probes = [](glm::ivec3 c) { return double(c.x) * c.y * c.z; };
    double fits = longest, over = longest / 1024.0;
    for (int i = 0; i < 60; ++i) {
        const double h = 0.5 * (fits + over);
        (probes(countsAt(h)) <= double(std::max(budget, 8)) ? fits : over) = h;
    }
    ProbeGrid g;
    g.counts = countsAt(fits);
    for (int a = 0; a < 3; ++a) {
        g.spacing[a] = extent[a] / float(g.counts[a]);
        g.origin[a] = lo[a] + 0.5f * g.spacing[a];
    }
    return g;
}

ProbeField::ProbeField(const Frame& frame, const ProbeFieldSettings& settings)
    : settings_(settings), grid_(probeGridFor(frame.gpuScene().bounds(), settings.probes))
{
    if (!settings_.relocation && !settings_.classification) settings_.fixedRays = 0;
    const int n = grid_.probes();
    columns_ = int(std::ceil(std::sqrt(double(n))));
    rows_ = (n + columns_ - 1) / columns_;
    maxDistance_ = 1.5f * glm::length(grid_.spacing);
    irradiance_ = Texture::create2D("ddgi.irradiance", GL_RGBA32F, columns_ * kIrradianceTile, rows_ * kIrradianceTile);
    depth_ = Texture::create2D("ddgi.depth", GL_RG32F, columns_ * kDepthTile, rows_ * kDepthTile);
    for (Texture* t : {&irradiance_, &depth_}) {
        t->setFilter(GL_LINEAR, GL_LINEAR);
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearTexImage(t->id(), 0, GL_RGBA, GL_FLOAT, zero);
    }
    // Every probe at its grid point and active until classification says otherwise.
    states_ = Buffer::fromVector("ddgi.probes", std::vector<glm::vec4>(std::size_t(n), glm::vec4(0, 0, 0, 1)));
    rays_ = Buffer("ddgi.rays",
                   std::size_t(n) * std::size_t(settings_.fixedRays + settings_.raysPerProbe) * sizeof(glm::vec4));
    trace_ = DirectLitProgram("ddgi.trace", "technique/ddgi/ddgi_trace.comp", traceDefines(frame, settings_));
    if (settings_.fixedRays > 0)
        state_ = Program::compute("ddgi.probe-state", "technique/ddgi/ddgi_probe_state.comp", stateDefines(settings_));
    std::vector<Define> update;
    if (settings_.fastTransitions) update.push_back({"FAST_TRANSITIONS", "1"});
    updateIrradiance_ = Program::compute("ddgi.update-irradiance", "technique/ddgi/ddgi_update.comp", update);
    update.push_back({"DEPTH", "1"});
    updateDepth_ = Program::compute("ddgi.update-depth", "technique/ddgi/ddgi_update.comp", update);
    shade_ = Program::compute("ddgi.shade", "technique/ddgi/ddgi_shade.comp", frame.gbufferDefines());
}

double ProbeField::raysPerFrame() const
{
    return double(grid_.probes()) * double(settings_.fixedRays + settings_.raysPerProbe);
}

void ProbeField::setGrid(Program& program) const
{
    program.set("gridOrigin", grid_.origin);
    program.set("gridSpacing", grid_.spacing);
    program.set("gridCounts", grid_.counts);
    program.set("atlasColumns", columns_);
    program.set("raysPerProbe", settings_.raysPerProbe);
    program.set("fixedRays", settings_.fixedRays);
    program.set("selfShadowBias", settings_.selfShadowBias);
}

glm::mat3 ProbeField::rotation() const
{
    // A uniform random rotation from three uniform numbers (Shoemake 1992, "Uniform random rotations").
    const std::uint64_t k = std::uint64_t(updates_) * 3u;
    const double u1 = unit(splitMix64(k)), u2 = unit(splitMix64(k + 1)), u3 = unit(splitMix64(k + 2));
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1), t1 = 2.0 * M_PI * u2, t2 = 2.0 * M_PI * u3;
    const glm::quat q(float(b * std::cos(t2)), float(a * std::sin(t1)), float(a * std::cos(t1)),
                      float(b * std::sin(t2)));
    return glm::mat3_cast(glm::normalize(q));
}

void ProbeField::update(Frame& frame, PassTimers& timers)
{
    const int n = grid_.probes(), perProbe = settings_.fixedRays + settings_.raysPerProbe;
    const glm::mat3 r = rotation();
    states_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_DDGI_PROBES);
    rays_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_DDGI_RAYS);
    {
        // ddgi_trace.comp per ray: its direction, a BVH walk (closestHitWork), the hit decoded (152 bytes, a
        // texel where the scene has textures), the frame's direct light there, and with bounces the eight
        // probes' lookups (two texels and the state each); the result written. A bound: every ray taken to hit.
        const double punctual = frame.gpuScene().punctualLightCount(), area = frame.lights().count() - punctual;
        const PassCost lights = directLightsCost(frame, punctual, area);
        PassCost cost;
        cost.flops = 215 + lights.flops + (settings_.bounces ? 8 * 90 : 0);
        cost.fetches = (frame.gpuScene().hasTextures() ? 4 : 0) + lights.fetches + (settings_.bounces ? 16 : 0);
        cost.bytesRead = 152 + lights.bytesRead + (settings_.bounces ? 8 * (16 + 4 * 16 + 4 * 8) : 0);
        cost.bytesWritten = 16;
        auto t = timers.scope("probe-trace", cost);
        t.expectComputes(computeInvocations({perProbe, n, 1}, {kTraceGroup, 1, 1}));
        t.addWork(closestHitWork(frame.rayCaster(), raysPerFrame()));
        Program& program = trace_.forFrame(frame);
        frame.bindSceneData();
        frame.rayCaster().bind();
        setGrid(program);
        program.set("rayRotation", r);
        program.set("seed", std::uint32_t(splitMix64(std::uint64_t(updates_) ^ 0x5151u)));
        irradiance_.bind(UNIT_DDGI_IRRADIANCE);
        depth_.bind(UNIT_DDGI_DEPTH);
        dispatchCompute(program, {perProbe, n, 1}, {kTraceGroup, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        // ddgi_update.comp per inner texel. Irradiance: every rotated ray of its probe from shared memory (its
        // share of the loads and directions, then a dot product, a weight and three sums each). Moments: its
        // share of sorting the rays into texels (a direction, an encode, two atomics), then the rays of the 25
        // texels around it (a dot product, the weight's seven products, two sums each). Both: the texel read,
        // the blend, and the tile's texels written from shared memory (side^2 / inner^2 each).
        const double rays = settings_.raysPerProbe;
        const int irradianceInner = kIrradianceTile - 2, depthInner = kDepthTile - 2;
        const double irradianceTexels = double(n) * irradianceInner * irradianceInner;
        const double depthTexels = double(n) * depthInner * depthInner;
        PassCost irradiance;
        irradiance.flops = 12.0 * rays + 40.0 * rays / 36.0 + 40;
        irradiance.bytesRead = 16 + 16.0 * rays * (1.0 + 1.0 / 36.0);
        irradiance.bytesWritten = 16.0 * 64.0 / 36.0;
        PassCost depth;
        const double nearRays = 25.0 * rays / double(depthInner * depthInner);
        depth.flops = 20.0 * nearRays + 60.0 * rays / 196.0 + 40;
        depth.bytesRead = 8 + 20.0 * nearRays + 16.0 * rays / 196.0;
        depth.bytesWritten = 8.0 * 256.0 / 196.0;
        PassCost cost = kernelWork(irradianceTexels, irradiance);
        const PassCost d = kernelWork(depthTexels, depth);
        cost.flopsFixed += d.flopsFixed;
        cost.bytesFixed += d.bytesFixed;
        cost.fetchesFixed = irradianceTexels + depthTexels;
        auto t = timers.scope("probe-update", cost);
        t.expectComputes(double(n) * (irradianceInner * irradianceInner + depthInner * depthInner));
        int inner = irradianceInner;
        for (Program* p : {&updateIrradiance_, &updateDepth_}) {
            setGrid(*p);
            p->set("rayRotation", r);
            p->set("hysteresis", settings_.hysteresis);
            p->set("maxDistance", maxDistance_);
            (p == &updateIrradiance_ ? irradiance_ : depth_).bindImage(0, GL_READ_WRITE);
            dispatchCompute(*p, {n * inner, inner, 1}, {inner, inner, 1});
            inner = depthInner;
        }
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    if (state_) {
        // After the blend: the states the rays were cast with are the ones the blend skips by; a probe
        // relocated or (in)activated here casts from its new state next frame.
        // ddgi_probe_state.comp per probe: its fixed rays read, their directions, the state read and written.
        PassCost cost;
        cost.flops = 40.0 * settings_.fixedRays + 30;
        cost.bytesRead = 16.0 * settings_.fixedRays + 16;
        cost.bytesWritten = 16;
        auto t = timers.scope("probe-state", cost);
        t.expectComputes(computeInvocations({n, 1, 1}, {kTraceGroup, 1, 1}));
        setGrid(state_);
        state_.set("probeCount", n);
        state_.set("minFrontDistance", 0.2f * std::min(grid_.spacing.x, std::min(grid_.spacing.y, grid_.spacing.z)));
        dispatchCompute(state_, {n, 1, 1}, {kTraceGroup, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    ++updates_;
}

void ProbeField::shade(Frame& frame, PassTimers& timers)
{
    // ddgi_shade.comp per pixel: its surface and BRDF read, eight probes' states and two bilinear lookups
    // each (four texels), the weights, the target written.
    PassCost cost;
    cost.flops = 60 + 8 * 90;
    cost.fetches = 4 + 16;
    cost.bytesRead = 8 + 16 + 8 * (16 + 4 * 16 + 4 * 8);
    cost.bytesWritten = 16;
    auto t = timers.scope("shade", cost);
    t.expectComputes(computeInvocations({frame.width(), frame.height(), 1}, {8, 8, 1}));
    frame.bindGBuffer();
    states_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_DDGI_PROBES);
    irradiance_.bind(UNIT_DDGI_IRRADIANCE);
    depth_.bind(UNIT_DDGI_DEPTH);
    setGrid(shade_);
    shade_.set("viewport", glm::ivec2(frame.width(), frame.height()));
    shade_.set("cameraPosition", frame.camera().position);
    frame.indirect().bindImage(0, GL_WRITE_ONLY);
    dispatchCompute(shade_, {frame.width(), frame.height(), 1}, {8, 8, 1});
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

std::vector<glm::vec4> ProbeField::probeStates() const
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    return states_.download<glm::vec4>();
}

} // namespace bounce::gl
