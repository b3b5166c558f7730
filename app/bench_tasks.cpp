#include "app/bench_tasks.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>

#include "app/commands.h"
#include "core/hash.h"
#include "core/light_paths.h"
#include "gl/technique/technique.h"

namespace bounce::app {

namespace {

std::string sizeText(int w, int h)
{
    return std::to_string(w) + "x" + std::to_string(h);
}

// FNV-1a, 64 bits, as 16 hex digits: stable across machines and compilers (std::hash is neither).
std::string hashText(const std::string& text)
{
    return core::Fnv1a().add(text).hex();
}

std::string joined(const std::vector<std::string>& items)
{
    std::string s;
    for (const std::string& i : items) s += i + ";";
    return s;
}

// What decides a task's figures: everything of the config that reaches its renders and comparisons.
std::string referenceKey(const ReferenceSpec& r)
{
    char buf[96];
    std::snprintf(buf, sizeof buf, "spp=%d noise=%.17g size=%s", r.spp, r.noise, sizeText(r.width, r.height).c_str());
    return buf;
}

std::string taskKey(const BenchConfig& config, const BenchTask& t)
{
    std::string key = std::string(kindName(t.kind)) + "|" + config.sceneNames[t.scene] + "|" + t.technique + "|" +
                      t.params + "|" + sizeText(t.width, t.height) + "|" + referenceKey(config.reference);
    if (t.kind == BenchTask::Kind::Render) {
        const BenchSetting& s = config.settings[t.setting];
        key += "|warmup=" + std::to_string(config.warmupOf(s)) + " frames=" + std::to_string(config.framesOf(s)) +
               "|baseline=" + s.baseline + " " + joined(s.baselineSets) +
               "|temporal=" + std::to_string(s.temporalFrames) + "|curve=" + std::to_string(s.curve) +
               "|compareTo=" + joined(config.compareTo);
        if (s.isPath())
            key += "|path=" + s.pathText + " every=" + std::to_string(s.every) +
                   " indirectScale=" + std::to_string(s.indirectScale) +
                   " stillFrames=" + std::to_string(s.stillFrames);
    }
    return key;
}

} // namespace

const char* kindName(BenchTask::Kind kind)
{
    switch (kind) {
    case BenchTask::Kind::Reference: return "reference";
    case BenchTask::Kind::Render: return "render";
    case BenchTask::Kind::PathTracer: return "path-tracer";
    case BenchTask::Kind::Rays: return "rays";
    }
    return "?";
}

std::vector<BenchTask> benchTasks(const BenchConfig& config)
{
    std::vector<BenchTask> references, rows;
    // The references app/bench_run.cpp reads, per scene, in the order it first reads them: `full` for the
    // path tracer's rows; per render its own light paths, `full`, "compareTo", `direct` (the frame's direct
    // light), at the reference's size or else the render's.
    std::set<std::string> seen;
    const auto reference = [&](std::size_t scene, const std::string& paths, int w, int h) {
        if (!seen.insert(std::to_string(scene) + " " + paths + "@" + sizeText(w, h)).second) return;
        BenchTask t;
        t.kind = BenchTask::Kind::Reference;
        t.scene = scene;
        t.technique = paths;
        t.params = sizeText(w, h);
        t.width = w;
        t.height = h;
        references.push_back(t);
    };
    const ReferenceSpec& ref = config.reference;
    for (std::size_t si = 0; si < config.sceneNames.size(); ++si) {
        const std::string& scene = config.sceneNames[si];
        const int pw = ref.width > 0 ? ref.width : config.width, ph = ref.height > 0 ? ref.height : config.height;
        if (!config.pathTracerSpp.empty()) reference(si, "full", pw, ph);
        for (int spp : config.pathTracerSpp) {
            BenchTask t;
            t.kind = BenchTask::Kind::PathTracer;
            t.scene = si;
            t.technique = "path-tracer";
            t.params = "spp=" + std::to_string(spp);
            t.width = pw;
            t.height = ph;
            t.spp = spp;
            t.row = rows.size();
            rows.push_back(t);
        }
        for (std::size_t k = 0; k < config.settings.size(); ++k) {
            const BenchSetting& s = config.settings[k];
            if (!s.runsOn(scene)) continue;
            const int rw = ref.width > 0 ? ref.width : config.widthOf(s);
            const int rh = ref.height > 0 ? ref.height : config.heightOf(s);
            // A camera-path run reads references of its frames' cameras, which it computes (or finds in
            // the cache) itself: one per measured frame, not the scene's still references.
            if (!s.isPath()) {
                reference(si, core::lightPathsName(gl::findTechnique(s.technique).lightPaths), rw, rh);
                reference(si, "full", rw, rh);
                for (const std::string& p : config.compareTo) reference(si, p, rw, rh);
                reference(si, "direct", rw, rh);
            }
            BenchTask t;
            t.kind = BenchTask::Kind::Render;
            t.scene = si;
            t.technique = s.technique;
            t.params = settingsText(s.sets);
            t.setting = k;
            t.width = config.widthOf(s);
            t.height = config.heightOf(s);
            t.row = rows.size();
            rows.push_back(t);
        }
    }
    std::vector<BenchTask> tasks = references;
    tasks.insert(tasks.end(), rows.begin(), rows.end());
    // The "rays" table, measured after the renders as a one-machine run does: a task per scene.
    if (config.rays > 0)
        for (std::size_t si = 0; si < config.sceneNames.size(); ++si) {
            BenchTask t;
            t.kind = BenchTask::Kind::Rays;
            t.scene = si;
            t.technique = "ray-casting";
            t.params = "rays=" + std::to_string(config.rays);
            tasks.push_back(t);
        }
    // A config may hold the same run twice: the second is another task (its own row and images).
    std::map<std::string, int> occurrences;
    for (std::size_t i = 0; i < tasks.size(); ++i) {
        tasks[i].index = i;
        const std::string key = taskKey(config, tasks[i]);
        const int n = occurrences[key]++;
        tasks[i].id = hashText(n == 0 ? key : key + "#" + std::to_string(n));
    }
    return tasks;
}

std::string taskLine(const BenchTask& t, const BenchConfig& config)
{
    std::string params = t.params;
    if (t.kind == BenchTask::Kind::Render) {
        const BenchSetting& s = config.settings[t.setting];
        params += " size=" + std::to_string(t.width) + "x" + std::to_string(t.height);
        if (s.isPath())
            params += " path=" + s.pathFile + " every=" + std::to_string(s.every) +
                      " indirectScale=" + std::to_string(s.indirectScale) +
                      " stillFrames=" + std::to_string(s.stillFrames);
        else
            params += " warmup=" + std::to_string(config.warmupOf(s)) + " frames=" + std::to_string(config.framesOf(s));
    }
    return std::to_string(t.index) + "\t" + t.id + "\t" + kindName(t.kind) + "\t" + config.sceneNames[t.scene] + "\t" +
           t.technique + "\t" + params;
}

namespace {

// A whole non-negative decimal number, nothing else (no sign, no spaces, no "1e3").
bool wholeNumber(const std::string& s, long long& value)
{
    if (s.empty() || s.size() > 9) return false;
    for (char c : s)
        if (c < '0' || c > '9') return false;
    value = std::stoll(s);
    return true;
}

} // namespace

Shard parseShard(const std::string& text)
{
    const std::size_t slash = text.find('/');
    long long i = 0, n = 0;
    if (slash == std::string::npos || !wholeNumber(text.substr(0, slash), i) ||
        !wholeNumber(text.substr(slash + 1), n) || n < 1 || i >= n)
        throw UsageError("--shard must be I/N with whole numbers 0 <= I < N (e.g. 0/4 ... 3/4), not '" + text + "'");
    return {int(i), int(n)};
}

bool slurmShard(Shard& shard)
{
    const auto env = [](const char* name) -> std::string {
        const char* v = std::getenv(name);
        return v ? v : "";
    };
    const std::string id = env("SLURM_ARRAY_TASK_ID");
    if (id.empty()) return false;
    long long task = 0, min = 0, step = 1, count = 0;
    const std::string stepText = env("SLURM_ARRAY_TASK_STEP");
    if (!wholeNumber(id, task) || !wholeNumber(env("SLURM_ARRAY_TASK_MIN"), min) ||
        !wholeNumber(env("SLURM_ARRAY_TASK_COUNT"), count) || (!stepText.empty() && !wholeNumber(stepText, step)) ||
        step < 1 || task < min || (task - min) % step != 0 || count < 1 || (task - min) / step >= count)
        throw UsageError("under a Slurm array, SLURM_ARRAY_TASK_ID (" + id + "), SLURM_ARRAY_TASK_MIN (" +
                         env("SLURM_ARRAY_TASK_MIN") + "), SLURM_ARRAY_TASK_STEP (" + stepText +
                         ") and SLURM_ARRAY_TASK_COUNT (" + env("SLURM_ARRAY_TASK_COUNT") +
                         ") do not make a shard; give --shard I/N");
    shard = {int((task - min) / step), int(count)};
    return true;
}

} // namespace bounce::app
