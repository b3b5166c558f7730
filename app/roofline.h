// Every pass against its own bound: the work a pass did (PassWork: invocations counted by the driver,
// flops, fetches and bytes from the pass's declared PassCost) at this machine's measured ceilings
// (gl::Ceilings, `bounce probe`). boundMs is the largest of the arithmetic, fetch, memory, uniform-read and
// triangle-setup times, so a
// pass at efficiency 1 runs as fast as the machine allows for the work it does; a pass far below is a
// finding to explain or to fix.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "gl/probe/machine_probe.h"
#include "gl/resource/timer.h"

namespace bounce::app {

struct PassBound {
    double computeMs = 0.0;  // flops at the FMA ceiling of the pass's stage
    double fetchMs = 0.0;    // texel fetches at the fetch ceiling
    double memoryMs = 0.0;   // bytes at the bandwidth ceiling
    double uniformMs = 0.0;  // uniform-block words at the rate a gather's loop reads them
    double setupMs = 0.0;    // triangles at the rasteriser's setup rate
    double boundMs = 0.0;    // the largest of the five
    double efficiency = 0.0; // boundMs / measured ms
    std::string limiter;     // "compute", "fetch", "memory", "uniform" or "setup"
};

// The bound of a pass that declared its cost and ran counted invocations; empty otherwise. A pass with
// both fragment and compute invocations is charged each stage's share at that stage's ceilings.
std::optional<PassBound> passBound(const gl::PassStat& pass, const gl::Ceilings& ceilings);

// The pass's work as the run record holds it (invocations, flops, fetches, bytes), with boundMs,
// efficiency and limiter when `ceilings` is given and the pass has a bound.
nlohmann::json passWorkJson(const gl::PassStat& pass, const gl::Ceilings* ceilings);

// Where the ceilings of a renderer are cached: <reference cache folder>/probe-<hash of renderer>.json.
std::string ceilingsCachePath(const std::string& renderer);
// The cached ceilings of this renderer, if `bounce probe` measured them; a damaged entry is ignored.
std::optional<gl::Ceilings> cachedCeilings(const std::string& renderer);
void storeCeilings(const gl::Ceilings& ceilings);
// Measures the ceilings on the current context (with a progress line on stderr) and caches them.
gl::Ceilings measureCeilings(bool quiet = false);

} // namespace bounce::app
