#include "app/bench_shard.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <cerrno>
#include <csignal>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "app/bench_report.h"
#include "app/bench_run.h"
#include "app/commands.h"
#include "app/render_job.h"
#include "app/roofline.h"
#include "core/image.h"

namespace bounce::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A task record keeps every figure as it was, NaN and infinities included: JSON has neither, so they go as
// the strings "NaN", "Infinity" and "-Infinity" (words no record uses otherwise) and come back as doubles.
json encodeDoubles(const json& j)
{
    if (j.is_number_float() && !std::isfinite(j.get<double>())) {
        const double v = j.get<double>();
        return std::isnan(v) ? "NaN" : v > 0 ? "Infinity" : "-Infinity";
    }
    if (j.is_structured()) {
        json out = j;
        for (auto it = out.begin(); it != out.end(); ++it) *it = encodeDoubles(*it);
        return out;
    }
    return j;
}

json decodeDoubles(const json& j)
{
    if (j.is_string()) {
        const std::string& s = j.get_ref<const std::string&>();
        if (s == "NaN") return std::numeric_limits<double>::quiet_NaN();
        if (s == "Infinity") return std::numeric_limits<double>::infinity();
        if (s == "-Infinity") return -std::numeric_limits<double>::infinity();
        return j;
    }
    if (j.is_structured()) {
        json out = j;
        for (auto it = out.begin(); it != out.end(); ++it) *it = decodeDoubles(*it);
        return out;
    }
    return j;
}

json rowJson(const BenchRow& r)
{
    return encodeDoubles({{"scene", r.scene},
                          {"technique", r.technique},
                          {"settings", r.settings},
                          {"size", r.size},
                          {"lightPaths", r.lightPaths},
                          {"baseline", r.baseline},
                          {"passes", r.passes},
                          {"totalMs", r.totalMs},
                          {"relRmseOwn", r.relRmseOwn},
                          {"relRmseFull", r.relRmseFull},
                          {"rmseOwn", r.rmseOwn},
                          {"ssimOwn", r.ssimOwn},
                          {"relRmseBaseline", r.relRmseBaseline},
                          {"flicker", r.flicker},
                          {"relRmseDirectLight", r.relRmseDirectLight},
                          {"relRmseCompareTo", r.relRmseCompareTo},
                          {"nonFiniteValues", r.nonFiniteValues},
                          {"record", r.record}});
}

BenchRow rowFrom(const json& encoded)
{
    const json j = decodeDoubles(encoded);
    BenchRow r;
    r.scene = j.at("scene");
    r.technique = j.at("technique");
    r.settings = j.at("settings");
    r.size = j.at("size");
    r.lightPaths = j.at("lightPaths");
    r.baseline = j.at("baseline");
    r.passes = j.at("passes");
    r.totalMs = j.at("totalMs");
    r.relRmseOwn = j.at("relRmseOwn");
    r.relRmseFull = j.at("relRmseFull");
    r.rmseOwn = j.at("rmseOwn");
    r.ssimOwn = j.at("ssimOwn");
    r.relRmseBaseline = j.at("relRmseBaseline");
    r.flicker = j.at("flicker");
    r.relRmseDirectLight = j.at("relRmseDirectLight");
    r.relRmseCompareTo = j.at("relRmseCompareTo").get<std::vector<double>>();
    r.nonFiniteValues = j.at("nonFiniteValues");
    r.record = j.at("record");
    return r;
}

std::string fileText(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw UsageError("cannot read " + path.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The task list as the manifest holds it: what --list-tasks prints, as objects.
json taskListJson(const BenchConfig& config, const std::vector<BenchTask>& tasks)
{
    json list = json::array();
    for (const BenchTask& t : tasks)
        list.push_back(
            {{"index", t.index},
             {"id", t.id},
             {"kind", kindName(t.kind)},
             {"scene", config.sceneNames[t.scene]},
             {"technique", t.technique},
             {"params", t.params},
             {"row",
              t.kind == BenchTask::Kind::Reference || t.kind == BenchTask::Kind::Rays ? json(nullptr) : json(t.row)}});
    return list;
}

json manifestJson(const BenchConfig& config, const ShardRun& run, const std::vector<BenchTask>& tasks)
{
    json configJson;
    try {
        configJson = json::parse(fileText(run.configPath));
    } catch (const json::exception& e) {
        throw UsageError("bench config: " + std::string(e.what()));
    }
    return {{"config", configJson},
            {"configPath", run.configPath},
            {"full", run.full},
            {"sourceHash", sourceHash()},
            // What the merge's report needs of the config, without loading its scenes.
            {"report",
             {{"sceneNames", config.sceneNames},
              {"compareTo", config.compareTo},
              {"width", config.width},
              {"height", config.height},
              {"warmup", config.warmup},
              {"frames", config.frames}}},
            {"tasks", taskListJson(config, tasks)}};
}

json readJson(const fs::path& path)
{
    try {
        return json::parse(fileText(path));
    } catch (const json::exception& e) {
        throw UsageError(path.string() + ": " + e.what());
    }
}

// The record of a task that this build need not run again: one of the same source hash.
bool doneBefore(const fs::path& record)
{
    if (!fs::exists(record)) return false;
    try {
        return json::parse(fileText(record)).value("sourceHash", "") == sourceHash();
    } catch (const std::exception&) {
        return false; // unreadable: run again (records are written whole, so this is another writer's file)
    }
}

// Moves every file of staging/images into out/images, each by one rename: a reader (the page, the merge)
// never sees half an image, and two shards writing the same reference leave one whole.
void moveImages(const fs::path& staging, const fs::path& out)
{
    if (!fs::exists(staging / "images")) return;
    fs::create_directories(out / "images");
    for (const fs::directory_entry& e : fs::directory_iterator(staging / "images"))
        fs::rename(e.path(), out / "images" / e.path().filename());
}

// A task killed part way (a time limit, scancel) leaves its staging folder, ID.HOST.PID. When the task runs
// again on the same host, the folders of its earlier runs whose process is gone are removed; a run still
// at work (the same shard started twice) keeps its own.
void removeDeadStaging(const fs::path& stagingDir, const std::string& id, const std::string& host)
{
    if (!fs::exists(stagingDir)) return;
    const std::string prefix = id + "." + host + ".";
    for (const fs::directory_entry& e : fs::directory_iterator(stagingDir)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        const std::string pid = name.substr(prefix.size());
        if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) continue;
        if (::kill(pid_t(std::stol(pid)), 0) != 0 && errno == ESRCH) fs::remove_all(e.path());
    }
}

} // namespace

int runBenchShard(const BenchConfig& config, const ShardRun& run)
{
    const std::vector<BenchTask> tasks = benchTasks(config);
    const json manifest = manifestJson(config, run, tasks);
    const fs::path manifestPath = run.out / "manifest.json";
    if (fs::exists(manifestPath)) {
        const json before = readJson(manifestPath);
        if (before.value("tasks", json()) != manifest["tasks"])
            throw UsageError(run.out.string() + " holds the tasks of another config (" +
                             before.value("configPath", std::string("?")) + "); give each config its own --out");
    }
    std::size_t mine = 0;
    for (const BenchTask& t : tasks) mine += int(t.index % std::size_t(run.shard.count)) == run.shard.index;
    fs::create_directories(run.out / "tasks");
    core::writeFileAtomic(manifestPath.string(), manifest.dump(2) + "\n");

    auto context = createContextForCli(run.backend);
    const gl::ContextInfo& info = context->info();
    std::printf("GL renderer: %s (%s); shard %d/%d: %zu of %zu tasks, source %s\n", info.renderer.c_str(),
                info.platform.c_str(), run.shard.index, run.shard.count, mine, tasks.size(), sourceHash());
    if (run.roofline && !cachedCeilings(info.renderer)) {
        std::printf("measuring this machine's ceilings (bounce probe), once per renderer\n");
        measureCeilings();
    }
    const std::string host = hostName();
    std::size_t failed = 0;
    for (const BenchTask& t : tasks) {
        if (int(t.index % std::size_t(run.shard.count)) != run.shard.index) continue;
        const fs::path recordPath = run.out / "tasks" / (t.id + ".json");
        const std::string line = taskLine(t, config);
        if (doneBefore(recordPath)) {
            std::printf("done before: %s\n", line.c_str());
            continue;
        }
        std::printf("task %s\n", line.c_str());
        std::fflush(stdout);
        const auto start = std::chrono::steady_clock::now();
        json record = {{"id", t.id},
                       {"index", t.index},
                       {"kind", kindName(t.kind)},
                       {"scene", config.sceneNames[t.scene]},
                       {"technique", t.technique},
                       {"params", t.params},
                       {"sourceHash", sourceHash()},
                       {"host", host},
                       {"renderer", info.renderer},
                       {"glVersion", info.version},
                       {"platform", info.platform}};
        removeDeadStaging(run.out / "staging", t.id, host);
        if (t.kind == BenchTask::Kind::Rays) {
            json figures = json::object();
            for (const RayThroughput& f : measureRayThroughput(config.scenes[t.scene], config.rays, 3, 0))
                figures[f.kind] = encodeDoubles(f.toJson());
            record["rays"] = figures;
        } else if (t.kind == BenchTask::Kind::Reference) {
            // Into the shared cache (ref/: concurrent writers each rename a whole file); the renders that
            // compare with it write it into images/ beside themselves.
            referenceImage(config.scenes[t.scene], config.sceneNames[t.scene], t.technique, t.width, t.height,
                           config.reference);
        } else {
            const fs::path staging = run.out / "staging" / (t.id + "." + host + "." + std::to_string(::getpid()));
            const BenchRow row = runTaskRow(config, t, info, staging);
            moveImages(staging, run.out);
            fs::remove_all(staging);
            record["row"] = rowJson(row);
            if (row.nonFiniteValues > 0) {
                std::fprintf(stderr, "bounce bench: error: %s (%s) on %s wrote %zu NaN/Inf values\n",
                             row.technique.c_str(), row.settings.c_str(), row.scene.c_str(), row.nonFiniteValues);
                ++failed;
            }
        }
        record["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        core::writeFileAtomic(recordPath.string(), record.dump(2) + "\n");
    }
    std::error_code ignored;
    fs::remove(run.out / "staging", ignored); // only when empty: another shard may be staging there
    std::printf("shard %d/%d done: records in %s/tasks; `bounce bench --merge %s --out OUT` writes the report\n",
                run.shard.index, run.shard.count, run.out.string().c_str(), run.out.string().c_str());
    return failed == 0 ? 0 : 1;
}

int mergeBenchShards(const std::vector<fs::path>& dirs, const fs::path& out)
{
    if (dirs.empty()) throw UsageError("--merge needs at least one folder of shards");
    // Everything is read and checked before anything is written.
    std::vector<json> manifests;
    for (const fs::path& d : dirs) {
        if (!fs::exists(d / "manifest.json"))
            throw UsageError(d.string() + " has no manifest.json: not the --out of a sharded bench run");
        manifests.push_back(readJson(d / "manifest.json"));
    }
    const json& manifest = manifests.front();
    const std::string hash = manifest.value("sourceHash", "");
    for (std::size_t i = 1; i < manifests.size(); ++i) {
        if (manifests[i]["tasks"] != manifest["tasks"])
            throw UsageError(dirs[i].string() + " holds the tasks of another config than " + dirs[0].string());
        if (manifests[i].value("sourceHash", "") != hash)
            throw UsageError(dirs[i].string() + " was run from other sources (" + manifests[i].value("sourceHash", "") +
                             ") than " + dirs[0].string() + " (" + hash + ")");
    }
    std::map<std::string, json> records;
    std::set<std::string> stale;
    for (const fs::path& d : dirs) {
        if (!fs::exists(d / "tasks")) continue;
        for (const fs::directory_entry& e : fs::directory_iterator(d / "tasks")) {
            if (e.path().extension() != ".json") continue; // a temporary of a writer still at work
            const json r = readJson(e.path());
            const std::string id = r.value("id", "");
            if (r.value("sourceHash", "") != hash)
                stale.insert(id);
            else if (!records.count(id))
                records[id] = r;
        }
    }

    BenchConfig config;
    const json& report = manifest.at("report");
    config.sceneNames = report.at("sceneNames").get<std::vector<std::string>>();
    config.compareTo = report.at("compareTo").get<std::vector<std::string>>();
    config.width = report.at("width");
    config.height = report.at("height");
    config.warmup = report.at("warmup");
    config.frames = report.at("frames");
    std::vector<BenchRow> rows;
    std::vector<SceneRays> rays;
    std::vector<std::string> missing;
    for (const json& t : manifest.at("tasks")) {
        const std::string id = t.at("id");
        if (!records.count(id)) {
            missing.push_back(std::to_string(t.at("index").get<std::size_t>()) + " " + id + " " +
                              t.at("kind").get<std::string>() + " " + t.at("scene").get<std::string>() + " " +
                              t.at("technique").get<std::string>() + " (" + t.at("params").get<std::string>() + ")" +
                              (stale.count(id) ? ", its record is of other sources" : ""));
            continue;
        }
        const json& record = records[id];
        if (t.at("kind") == "rays") {
            SceneRays scene{t.at("scene").get<std::string>(), {}};
            for (const auto& [kind, figures] : record.at("rays").items())
                scene.figures.push_back(RayThroughput::fromJson(kind, decodeDoubles(figures)));
            rays.push_back(scene);
        } else if (t.at("kind") != "reference") {
            rows.push_back(rowFrom(record.at("row")));
        }
    }

    fs::create_directories(out / "images");
    for (const fs::path& d : dirs) {
        if (!fs::exists(d / "images") || fs::equivalent(d, out)) continue;
        for (const fs::directory_entry& e : fs::directory_iterator(d / "images"))
            if (e.is_regular_file())
                fs::copy_file(e.path(), out / "images" / e.path().filename(), fs::copy_options::overwrite_existing);
    }
    // The renderers whose timings the rows hold: one front per renderer when there are several.
    std::vector<std::string> renderers, platforms;
    for (const BenchRow& r : rows) {
        const std::string renderer = r.record.value("renderer", ""), platform = r.record.value("platform", "");
        if (std::find(renderers.begin(), renderers.end(), renderer) == renderers.end()) renderers.push_back(renderer);
        if (!platform.empty() && std::find(platforms.begin(), platforms.end(), platform) == platforms.end())
            platforms.push_back(platform);
    }
    const auto joinedText = [](const std::vector<std::string>& items) {
        std::string s;
        for (const std::string& i : items) s += (s.empty() ? "" : "; ") + i;
        return s;
    };
    std::vector<std::string> notes;
    const std::size_t total = manifest.at("tasks").size();
    if (!missing.empty())
        notes.push_back("Incomplete: " + std::to_string(missing.size()) + " of " + std::to_string(total) +
                        " tasks have no record (index, id, kind, scene, technique, parameters): " +
                        joinedText(missing) + ". Run their shards again with the same --out, then merge again.");
    if (renderers.size() > 1)
        notes.push_back("Timings from " + std::to_string(renderers.size()) + " GL renderers (" + joinedText(renderers) +
                        "): they do not compare, so each scene's Pareto front is that of one renderer's rows.");
    gl::ContextInfo context;
    context.renderer = joinedText(renderers);
    context.platform = joinedText(platforms);
    writeBenchReport(out, config, rows, rays, context, notes);
    const int rc = finishBenchReport(out, rows);
    std::printf("merged %zu of %zu tasks from %zu folder(s), source %s\n", total - missing.size(), total, dirs.size(),
                hash.c_str());
    for (const std::string& m : missing) std::fprintf(stderr, "bounce bench: missing task %s\n", m.c_str());
    return missing.empty() ? rc : 1;
}

} // namespace bounce::app
