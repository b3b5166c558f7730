#include "gl/probe/machine_probe.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "gl/context/context.h"
#include "gl/gl.h"
#include "gl/resource/buffer.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/pass_state.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"
#include "glsl/probe/bindings.glsl"

namespace bounce::gl {

namespace {

constexpr double kFlopsPerInvocation = 16 * 64.0; // kernels.glsl: FMA_STEPS x 64 flops per step
constexpr int kFetchesPerInvocation = 32;         // kernels.glsl: FETCHES
constexpr int kUniformRecords = 256;              // kernels.glsl: UNIFORM_RECORDS, all read per invocation
constexpr int kUniformWordsPerRecord = 12;        //   UNIFORM_WORDS_PER_RECORD
constexpr int kTriangleGridSide = 256;            // 2 x 256^2 triangles of 8 pixels on a 1024^2 target
constexpr int kFramebufferDraws = 4;              // blended, so that no draw can replace the one before
// A timed scope runs a kernel as many times as fill this long (at most kMaxRuns): a GPU finishes one
// full-screen kernel in tens of microseconds, where a timer's resolution and a draw's fixed cost are not
// negligible.
constexpr double kMinScopeMs = 20.0;
constexpr int kMaxRuns = 1024;

double wallMs(const std::function<void()>& work)
{
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    work();
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Milliseconds of one run of `work`: the median over `repeats` timed scopes (PassTimers, as passes are
// timed) of `runs` runs each, after one untimed run that also sizes `runs` (kMinScopeMs).
double timeKernel(const std::string& name, int repeats, const std::function<void()>& work)
{
    const double once = wallMs(work); // compiles, allocates, and says how long one run takes
    const int runs = std::clamp(int(std::ceil(kMinScopeMs / std::max(once, 1e-3))), 1, kMaxRuns);
    PassTimers timers;
    for (int r = 0; r <= repeats; ++r) {
        {
            auto scope = timers.scope("probe." + name);
            for (int i = 0; i < runs; ++i) work();
        }
        timers.endFrame(r > 0);
    }
    const std::vector<PassStat> stats = timers.stats();
    if (stats.empty() || !(stats.front().medianMs > 0.0))
        throw std::runtime_error("probe kernel " + name + " took no time");
    return stats.front().medianMs / runs;
}

class Probe {
public:
    explicit Probe(const ProbeOptions& o)
        : o_(o), n_(o.size), target_(Texture::create2D("probe.target", GL_RGBA32F, n_, n_)), fbo_("probe.fbo")
    {
        fbo_.attach(GL_COLOR_ATTACHMENT0, target_);
        fbo_.checkComplete();
        std::vector<float> ramp(std::size_t(n_) * n_ * 4);
        for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = float(i % 97) / 97.0f;
        for (int i = 0; i < 4; ++i) {
            inputs_.push_back(Texture::create2D("probe.input" + std::to_string(i), GL_RGBA32F, n_, n_));
            glTextureSubImage2D(inputs_.back().id(), 0, 0, 0, n_, n_, GL_RGBA, GL_FLOAT, ramp.data());
        }
        small_ = Texture::create2D("probe.small", GL_RGBA8, 64, 64);
        std::vector<unsigned char> bytes(64 * 64 * 4);
        for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = (unsigned char)(i * 31);
        glTextureSubImage2D(small_.id(), 0, 0, 0, 64, 64, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    }

    double pixels() const { return double(n_) * double(n_); }

    void fullscreen(Program& p, bool blend = false)
    {
        PassState s = PassState::fullscreen(fbo_, n_, n_);
        s.blend = blend;
        s.apply();
        p.use();
        vao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

    void compute(const Program& p)
    {
        target_.bindImage(0, GL_WRITE_ONLY);
        dispatchCompute(p, {n_, n_, 1}, {8, 8, 1});
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
    }

    Ceilings run()
    {
        Ceilings c;
        c.size = n_;
        c.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        const int total = 11;
        int done = 0;
        const auto step = [&](const char* kernel) {
            if (o_.progress) o_.progress(kernel, ++done, total);
        };
        const double flops = pixels() * kFlopsPerInvocation;
        {
            Program p = Program::graphics("probe.fma.frag", "frame/fullscreen.vert", "probe/fma.frag");
            setFma(p);
            c.fragmentGflops = flops / (timeKernel("fma.frag", o_.repeats, [&] { fullscreen(p); }) * 1e6);
            step("fragment FMA");
        }
        {
            Program p = Program::compute("probe.fma.comp", "probe/fma.comp");
            setFma(p);
            c.computeGflops = flops / (timeKernel("fma.comp", o_.repeats, [&] { compute(p); }) * 1e6);
            step("compute FMA");
        }
        {
            Program p = Program::graphics("probe.bandwidth.frag", "frame/fullscreen.vert", "probe/bandwidth.frag");
            for (int i = 0; i < 4; ++i) inputs_[i].bind(UNIT_PROBE_FIRST + i);
            const double bytes = pixels() * (4 * 16 + 16);
            c.fragmentGBps = bytes / (timeKernel("bandwidth.frag", o_.repeats, [&] { fullscreen(p); }) * 1e6);
            step("fragment bandwidth");
        }
        {
            Program p = Program::compute("probe.bandwidth.image", "probe/bandwidth_image.comp");
            inputs_[0].bind(UNIT_PROBE_FIRST);
            c.computeImageGBps = pixels() * 32 / (timeKernel("bandwidth.image", o_.repeats, [&] { compute(p); }) * 1e6);
            step("compute image bandwidth");
        }
        {
            const std::size_t count = std::size_t(n_) * n_;
            Buffer source("probe.source", count * 16), target("probe.target.buffer", count * 16);
            source.clearToZero();
            Program p = Program::compute("probe.bandwidth.buffer", "probe/bandwidth_buffer.comp");
            p.set("count", unsigned(count));
            source.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PROBE_SOURCE);
            target.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PROBE_TARGET);
            const double ms = timeKernel("bandwidth.buffer", o_.repeats, [&] {
                dispatchCompute(p, {int(count), 1, 1}, {64, 1, 1});
                glMemoryBarrier(GL_ALL_BARRIER_BITS);
            });
            c.computeBufferGBps = double(count) * 32 / (ms * 1e6);
            step("compute buffer bandwidth");
        }
        {
            Program p = Program::graphics("probe.fetch.frag", "frame/fullscreen.vert", "probe/fetch.frag");
            small_.bind(UNIT_PROBE_FIRST);
            const double fetches = pixels() * kFetchesPerInvocation;
            c.fragmentGfetches = fetches / (timeKernel("fetch.frag", o_.repeats, [&] { fullscreen(p); }) * 1e6);
            step("fragment fetch rate");
        }
        {
            Program p = Program::compute("probe.fetch.comp", "probe/fetch.comp");
            small_.bind(UNIT_PROBE_FIRST);
            const double fetches = pixels() * kFetchesPerInvocation;
            c.computeGfetches = fetches / (timeKernel("fetch.comp", o_.repeats, [&] { compute(p); }) * 1e6);
            step("compute fetch rate");
        }
        {
            // Every record of the block is read by every invocation: words = invocations x records x 12.
            std::vector<float> records(std::size_t(kUniformRecords) * kUniformWordsPerRecord);
            for (std::size_t i = 0; i < records.size(); ++i) records[i] = 1e-3f * float(i % 13);
            Buffer block("probe.records", records.size() * sizeof(float));
            glNamedBufferSubData(block.id(), 0, GLsizeiptr(records.size() * sizeof(float)), records.data());
            block.bindBase(GL_UNIFORM_BUFFER, UBO_PROBE_RECORDS);
            const double words = pixels() * kUniformRecords * kUniformWordsPerRecord;
            Program f = Program::graphics("probe.uniform.frag", "frame/fullscreen.vert", "probe/uniform.frag");
            f.set("count", kUniformRecords);
            c.fragmentGuniformWords = words / (timeKernel("uniform.frag", o_.repeats, [&] { fullscreen(f); }) * 1e6);
            step("fragment uniform reads");
            Program k = Program::compute("probe.uniform.comp", "probe/uniform.comp");
            k.set("count", kUniformRecords);
            c.computeGuniformWords = words / (timeKernel("uniform.comp", o_.repeats, [&] { compute(k); }) * 1e6);
            step("compute uniform reads");
        }
        {
            Program p = Program::graphics("probe.flat", "frame/fullscreen.vert", "probe/flat.frag");
            p.set("colour", glm::vec4(0.25f));
            const double bytes = pixels() * 32 * kFramebufferDraws; // blending reads and writes RGBA32F
            c.framebufferGBps = bytes / (timeKernel("framebuffer", o_.repeats,
                                                    [&] {
                                                        for (int i = 0; i < kFramebufferDraws; ++i) fullscreen(p, true);
                                                    }) *
                                         1e6);
            step("framebuffer bandwidth");
        }
        {
            Program p = Program::graphics("probe.triangles", "probe/triangles.vert", "probe/flat.frag");
            p.set("side", kTriangleGridSide);
            p.set("colour", glm::vec4(0.5f));
            const double triangles = 2.0 * kTriangleGridSide * kTriangleGridSide;
            const double ms = timeKernel("triangles", o_.repeats, [&] {
                PassState s = PassState::fullscreen(fbo_, n_, n_);
                s.apply();
                p.use();
                vao_.bind();
                glDrawArrays(GL_TRIANGLES, 0, GLsizei(triangles * 3));
            });
            c.mtrianglesPerSecond = triangles / (ms * 1e3);
            step("triangle setup");
        }
        return c;
    }

private:
    ProbeOptions o_;
    int n_;
    Texture target_;
    Framebuffer fbo_;
    std::vector<Texture> inputs_;
    Texture small_;
    VertexArray vao_{"probe.vao"};

    static void setFma(Program& p)
    {
        p.set("a", glm::vec4(0.999f));
        p.set("b", glm::vec4(1e-3f));
    }
};

double positive(const nlohmann::json& j, const char* key)
{
    if (!j.contains(key) || !j[key].is_number() || !(j[key].get<double>() > 0.0) ||
        !std::isfinite(j[key].get<double>()))
        throw std::invalid_argument(std::string("ceilings: '") + key + "' must be a positive number");
    return j[key].get<double>();
}

} // namespace

nlohmann::json Ceilings::toJson() const
{
    return {{"renderer", renderer},
            {"size", size},
            {"fragmentGflops", fragmentGflops},
            {"computeGflops", computeGflops},
            {"fragmentGBps", fragmentGBps},
            {"computeImageGBps", computeImageGBps},
            {"computeBufferGBps", computeBufferGBps},
            {"fragmentGfetches", fragmentGfetches},
            {"computeGfetches", computeGfetches},
            {"fragmentGuniformWords", fragmentGuniformWords},
            {"computeGuniformWords", computeGuniformWords},
            {"framebufferGBps", framebufferGBps},
            {"mtrianglesPerSecond", mtrianglesPerSecond}};
}

Ceilings Ceilings::fromJson(const nlohmann::json& j)
{
    if (!j.is_object()) throw std::invalid_argument("ceilings: not a JSON object");
    Ceilings c;
    if (!j.contains("renderer") || !j["renderer"].is_string()) throw std::invalid_argument("ceilings: no 'renderer'");
    c.renderer = j["renderer"].get<std::string>();
    c.size = int(positive(j, "size"));
    c.fragmentGflops = positive(j, "fragmentGflops");
    c.computeGflops = positive(j, "computeGflops");
    c.fragmentGBps = positive(j, "fragmentGBps");
    c.computeImageGBps = positive(j, "computeImageGBps");
    c.computeBufferGBps = positive(j, "computeBufferGBps");
    c.fragmentGfetches = positive(j, "fragmentGfetches");
    c.computeGfetches = positive(j, "computeGfetches");
    c.fragmentGuniformWords = positive(j, "fragmentGuniformWords");
    c.computeGuniformWords = positive(j, "computeGuniformWords");
    c.framebufferGBps = positive(j, "framebufferGBps");
    c.mtrianglesPerSecond = positive(j, "mtrianglesPerSecond");
    return c;
}

Ceilings probeMachine(const ProbeOptions& options)
{
    if (options.size < 64 || options.size > 4096) throw std::invalid_argument("probe size must be in [64, 4096]");
    if (options.repeats < 1) throw std::invalid_argument("probe repeats must be at least 1");
    Probe probe(options);
    return probe.run();
}

namespace {
std::optional<Ceilings> knownCeilings;
} // namespace

void setKnownCeilings(const std::optional<Ceilings>& ceilings)
{
    knownCeilings = ceilings;
}

bool preferFragmentPasses()
{
    if (knownCeilings) return knownCeilings->fragmentGflops > knownCeilings->computeGflops;
    return softwareRasterizer();
}

} // namespace bounce::gl
