#include "app/roofline.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/hash.h"
#include "core/image.h"
#include "ref/reference.h"

namespace bounce::app {

std::optional<PassBound> passBound(const gl::PassStat& pass, const gl::Ceilings& c)
{
    const gl::PassWork& w = pass.work;
    const double invocations = w.fragmentInvocations + w.computeInvocations;
    if (!w.costDeclared || invocations <= 0.0 || pass.medianMs <= 0.0) return std::nullopt;
    // Each stage's share of the work at its own ceilings (a pass is nearly always one stage).
    const double f = w.fragmentInvocations / invocations, k = 1.0 - f;
    const auto ms = [](double amount, double perSecond) { return perSecond > 0.0 ? amount / perSecond * 1e3 : 0.0; };
    PassBound b;
    b.computeMs = ms(f * w.flops, c.fragmentGflops * 1e9) + ms(k * w.flops, c.computeGflops * 1e9);
    b.fetchMs = ms(f * w.fetches, c.fragmentGfetches * 1e9) + ms(k * w.fetches, c.computeGfetches * 1e9);
    b.memoryMs = ms(f * w.bytes, c.fragmentGBps * 1e9) + ms(k * w.bytes, c.computeGBps() * 1e9);
    b.uniformMs =
        ms(f * w.uniformWords, c.fragmentGuniformWords * 1e9) + ms(k * w.uniformWords, c.computeGuniformWords * 1e9);
    b.setupMs = ms(w.triangles, c.mtrianglesPerSecond * 1e6);
    b.boundMs = std::max({b.computeMs, b.fetchMs, b.memoryMs, b.uniformMs, b.setupMs});
    b.limiter = b.boundMs == b.computeMs   ? "compute"
                : b.boundMs == b.fetchMs   ? "fetch"
                : b.boundMs == b.memoryMs  ? "memory"
                : b.boundMs == b.uniformMs ? "uniform"
                                           : "setup";
    b.efficiency = b.boundMs / pass.medianMs;
    return b;
}

nlohmann::json passWorkJson(const gl::PassStat& p, const gl::Ceilings* ceilings)
{
    nlohmann::json j = {{"fragmentInvocations", p.work.fragmentInvocations},
                        {"computeInvocations", p.work.computeInvocations},
                        {"costDeclared", p.work.costDeclared}};
    if (p.work.costDeclared) {
        j["flops"] = p.work.flops;
        j["fetches"] = p.work.fetches;
        j["bytes"] = p.work.bytes;
        j["triangles"] = p.work.triangles;
        j["uniformWords"] = p.work.uniformWords;
    }
    if (ceilings)
        if (const auto b = passBound(p, *ceilings)) {
            j["computeMs"] = b->computeMs;
            j["fetchMs"] = b->fetchMs;
            j["memoryMs"] = b->memoryMs;
            j["uniformMs"] = b->uniformMs;
            j["setupMs"] = b->setupMs;
            j["boundMs"] = b->boundMs;
            j["efficiency"] = b->efficiency;
            j["limiter"] = b->limiter;
        }
    return j;
}

std::string ceilingsCachePath(const std::string& renderer)
{
    // FNV-1a of the renderer string: one file per driver, CPU and version as GL_RENDERER names them (the
    // legacy basis, core/hash.h: the probe files already written keep their names).
    const std::string name = "probe-" + core::Fnv1a(core::Fnv1a::kLegacyBasis).add(renderer).hex() + ".json";
    return (std::filesystem::path(ref::defaultCacheDir()) / name).string();
}

std::optional<gl::Ceilings> cachedCeilings(const std::string& renderer)
{
    std::ifstream in(ceilingsCachePath(renderer));
    if (!in) return std::nullopt;
    try {
        const gl::Ceilings c = gl::Ceilings::fromJson(nlohmann::json::parse(in));
        if (c.renderer != renderer) return std::nullopt;
        return c;
    } catch (const std::exception&) {
        return std::nullopt; // damaged: measured again by the next `bounce probe`
    }
}

void storeCeilings(const gl::Ceilings& c)
{
    const std::string path = ceilingsCachePath(c.renderer);
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    core::writeFileAtomic(path, c.toJson().dump(2) + "\n");
}

gl::Ceilings measureCeilings(bool quiet)
{
    gl::ProbeOptions o;
    if (!quiet)
        o.progress = [](const std::string& kernel, int done, int total) {
            std::fprintf(stderr, "\rprobe [%-*s] %d/%d %-28s", total, std::string(done, '#').c_str(), done, total,
                         kernel.c_str());
            if (done == total) std::fputc('\n', stderr);
        };
    const gl::Ceilings c = gl::probeMachine(o);
    storeCeilings(c);
    return c;
}

} // namespace bounce::app
