// A bench run split into shards (app/bench_tasks.h, app/bench_shard.h), end to end through the `bounce`
// executable: the task list is the same on every call and every task has its own id; a bad shard spec is
// refused before anything is written; two shards and a merge give the records of a one-machine run (every
// field but the timings and the host), a shard run again skips what it did, a record of other sources is
// run again, and a missing task makes the merge fail and is named in its report.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/app/run_command.h"
#include "tests/app/test_backend.h"

namespace {

namespace fs = std::filesystem;
using bounce::testing::testBackend;
using nlohmann::json;

using Result = bounce::testing::CommandRun;
using bounce::testing::runShell;

// `bounce ARGS` with the variables `env` ("NAME=value ...").
Result run(const std::string& args, const std::string& env = "")
{
    return bounce::testing::runBounce(args, env + " ");
}

fs::path outDir(const std::string& name)
{
    const fs::path d = fs::path(BOUNCE_TEST_OUT) / "bench-shard" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string text(const fs::path& path)
{
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::vector<std::string>> taskLines(const std::string& output)
{
    std::vector<std::vector<std::string>> lines;
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> fields(1);
        for (char c : line)
            if (c == '\t')
                fields.emplace_back();
            else
                fields.back() += c;
        lines.push_back(fields);
    }
    return lines;
}

// Two renders, a sweep, the path tracer and the ray-casting table on one scene, at 16x16, one frame:
// seconds on llvmpipe.
const char* kTinyConfig = R"({"size": "16x16", "warmup": 0, "frames": 1, "reference": {"spp": 16},
    "scenes": ["cornell-spot"], "pathTracerSpp": [4], "rays": 1024,
    "runs": [{"technique": "direct"}, {"technique": "rsm", "sweep": {"vpls": [4, 16]}}]})";

TEST(BenchShard, TaskListIsTheSameEveryTimeWithAnIdPerTask)
{
    const fs::path d = outDir("list");
    const fs::path config = d / "tiny.json";
    std::ofstream(config) << kTinyConfig;
    const Result a = run("bench --config " + config.string() + " --list-tasks");
    const Result b = run("bench --config " + config.string() + " --list-tasks");
    ASSERT_EQ(a.status, 0) << a.output;
    EXPECT_EQ(a.output, b.output);
    const auto lines = taskLines(a.output);
    // References: own light paths (direct, onebounce-novis), full, direct for the frame's direct light;
    // the path tracer, three renders; the ray-casting table.
    ASSERT_EQ(lines.size(), 3u + 1u + 3u + 1u) << a.output;
    std::set<std::string> ids;
    bool renders = false;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        ASSERT_EQ(lines[i].size(), 6u) << a.output;
        EXPECT_EQ(lines[i][0], std::to_string(i));
        EXPECT_EQ(lines[i][1].size(), 16u);
        ids.insert(lines[i][1]);
        EXPECT_EQ(lines[i][3], "cornell-spot");
        const std::string kind = lines[i][2];
        EXPECT_TRUE(kind == "reference" || kind == "render" || kind == "path-tracer" || kind == "rays") << kind;
        if (kind != "reference") renders = true;
        EXPECT_FALSE(renders && kind == "reference") << "references first:\n" << a.output;
    }
    EXPECT_EQ(ids.size(), lines.size()) << "an id per task:\n" << a.output;
    EXPECT_EQ(lines[6][4], "rsm");
    EXPECT_NE(lines[6][5].find("vpls=16"), std::string::npos) << a.output;
    EXPECT_EQ(lines.back()[2], "rays");
    EXPECT_EQ(lines.back()[5], "rays=1024");

    // One run's frames changed: its id changes, the others' do not.
    std::string other = kTinyConfig;
    other.replace(other.find(R"({"technique": "direct"})"), 23, R"({"technique": "direct", "frames": 2})");
    std::ofstream(d / "other.json") << other;
    const Result c = run("bench --config " + (d / "other.json").string() + " --list-tasks");
    ASSERT_EQ(c.status, 0) << c.output;
    const auto changed = taskLines(c.output);
    ASSERT_EQ(changed.size(), lines.size());
    int differ = 0;
    for (std::size_t i = 0; i < lines.size(); ++i) differ += changed[i][1] != lines[i][1];
    EXPECT_EQ(differ, 1) << a.output << c.output;
}

// A camera-path run is a task like any render (issue 61: "every kind of bench run is a task"): one line,
// no still references of its own (it reads those of its frames' cameras), and an id that covers what the
// path file says, not its name, and the measured frames.
TEST(BenchShard, CameraPathRunIsOneTaskWhoseIdCoversThePath)
{
    const fs::path d = outDir("list-path");
    const auto list = [&](const std::string& path, int every) {
        std::ofstream(d / "c.json") << R"({"size": "16x16", "scenes": ["cornell-spot"], "runs": [
            {"technique": "direct", "path": ")"
                                    << (d / path).string() << R"(", "every": )" << every << "}]}";
        const Result r = run("bench --config " + (d / "c.json").string() + " --list-tasks");
        EXPECT_EQ(r.status, 0) << r.output;
        return taskLines(r.output);
    };
    const std::string key = R"({"frame": 0, "camera": "0.278,0.273,-0.8:0.278,0.273,0.2795:39.3"})";
    std::ofstream(d / "a.json") << R"({"frames": 4, "keys": [)" + key + "]}";
    std::ofstream(d / "same.json") << R"({"keys": [)" + key + R"(], "frames": 4})";
    std::ofstream(d / "longer.json") << R"({"frames": 5, "keys": [)" + key + "]}";
    const auto a = list("a.json", 2);
    ASSERT_EQ(a.size(), 1u) << "no reference tasks for a camera-path run";
    EXPECT_EQ(a[0][2], "render");
    EXPECT_NE(a[0][5].find("every=2"), std::string::npos) << a[0][5];
    EXPECT_EQ(list("same.json", 2)[0][1], a[0][1]) << "the same path under another name and key order";
    EXPECT_NE(list("longer.json", 2)[0][1], a[0][1]) << "another path";
    EXPECT_NE(list("a.json", 3)[0][1], a[0][1]) << "other measured frames";
}

TEST(BenchShard, BadShardSpecExitsTwoAndWritesNothing)
{
    const fs::path d = outDir("bad");
    const fs::path config = d / "tiny.json";
    std::ofstream(config) << kTinyConfig;
    const fs::path out = d / "out";
    for (const std::string spec : {"3/3", "-1/2", "x/y", "0/0", "1", "1/2/3", "+1/2", "1/-2", ""}) {
        const Result r = run("bench --backend " + testBackend() + " --config " + config.string() + " --out " +
                             out.string() + " --cache " + (d / "cache").string() + " --shard '" + spec + "'");
        EXPECT_EQ(r.status, 2) << spec << "\n" << r.output;
        EXPECT_NE(r.output.find("--shard"), std::string::npos) << spec << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out)) << spec;
        EXPECT_FALSE(fs::exists(d / "cache")) << spec;
    }
    // A Slurm array's variables that make no shard (an id beyond the count).
    const Result r = run("bench --backend " + testBackend() + " --config " + config.string() + " --out " + out.string(),
                         "SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_COUNT=3");
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("SLURM_ARRAY_TASK_ID"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

// Everything of a record but what the machine and the moment decide: timings (every "...Ms", the passes'
// figures, the fronts drawn from them), the host and the time of day.
json withoutTimings(const json& j)
{
    if (j.is_array()) {
        json out = json::array();
        for (const json& v : j) out.push_back(withoutTimings(v));
        return out;
    }
    if (!j.is_object()) return j;
    json out = json::object();
    for (const auto& [k, v] : j.items()) {
        const bool timing = k.size() > 2 && (k.compare(k.size() - 2, 2, "Ms") == 0);
        if (timing || k == "host" || k == "time" || k == "pareto" || k == "passes") continue;
        out[k] = withoutTimings(v);
    }
    return out;
}

std::set<std::string> passNames(const json& record)
{
    std::set<std::string> names;
    for (const json& p : record.value("passes", json::array())) names.insert(p["pass"].get<std::string>());
    return names;
}

TEST(BenchShard, TwoShardsAndAMergeGiveTheRecordsOfOneMachine)
{
    const fs::path d = outDir("merge");
    const fs::path config = d / "tiny.json";
    std::ofstream(config) << kTinyConfig;
    const std::string common =
        "bench --backend " + testBackend() + " --config " + config.string() + " --cache " + (d / "cache").string();
    const Result whole = run(common + " --out " + (d / "whole").string());
    ASSERT_EQ(whole.status, 0) << whole.output;

    const fs::path shards = d / "shards";
    const Result s0 = run(common + " --out " + shards.string() + " --shard 0/2");
    ASSERT_EQ(s0.status, 0) << s0.output;
    // The second shard as a Slurm array task: ids 10 and 11, so 11 is shard 1 of 2.
    const Result s1 = run(common + " --out " + shards.string(),
                          "SLURM_ARRAY_TASK_ID=11 SLURM_ARRAY_TASK_MIN=10 SLURM_ARRAY_TASK_COUNT=2");
    ASSERT_EQ(s1.status, 0) << s1.output;
    EXPECT_NE(s1.output.find("shard 1/2"), std::string::npos) << s1.output;

    const json manifest = json::parse(text(shards / "manifest.json"));
    ASSERT_EQ(manifest["tasks"].size(), 8u);
    EXPECT_EQ(manifest["sourceHash"].get<std::string>().size(), 16u);
    EXPECT_EQ(manifest["config"]["pathTracerSpp"], json::array({4}));
    for (const json& t : manifest["tasks"]) {
        const fs::path record = shards / "tasks" / (t["id"].get<std::string>() + ".json");
        ASSERT_TRUE(fs::exists(record)) << t.dump();
        const json r = json::parse(text(record));
        EXPECT_EQ(r["sourceHash"], manifest["sourceHash"]);
        for (const char* key : {"host", "renderer", "glVersion"})
            EXPECT_FALSE(r.value(key, std::string()).empty()) << key << " in " << record;
    }
    EXPECT_FALSE(fs::exists(shards / "staging")) << "staging folders are removed";

    const fs::path merged = d / "merged";
    const Result m = run("bench --merge " + shards.string() + " --out " + merged.string());
    ASSERT_EQ(m.status, 0) << m.output;
    for (const char* f : {"results.csv", "results.json", "report.md", "report.html", "report-data.js"})
        EXPECT_TRUE(fs::exists(merged / f)) << f;
    const json a = json::parse(text(d / "whole" / "results.json"));
    const json b = json::parse(text(merged / "results.json"));
    ASSERT_EQ(a.size(), 4u);
    ASSERT_EQ(b.size(), a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(withoutTimings(b[i]), withoutTimings(a[i])) << "row " << i;
        EXPECT_EQ(passNames(b[i]), passNames(a[i])) << "row " << i;
        const std::string image = b[i].value("image", std::string());
        EXPECT_TRUE(fs::exists(merged / (image + ".js"))) << image;
        const json references = b[i].value("references", json::object());
        EXPECT_FALSE(references.empty()) << "row " << i;
        for (const auto& [paths, id] : references.items())
            EXPECT_TRUE(fs::exists(merged / (id.get<std::string>() + ".js"))) << paths;
    }
    EXPECT_EQ(text(merged / "report.md").find("Incomplete"), std::string::npos);
    // The ray-casting table, a task of its own: the same rays cast, the same triangles found.
    const json raysA = json::parse(text(d / "whole" / "rays.json"));
    const json raysB = json::parse(text(merged / "rays.json"));
    ASSERT_EQ(raysA.size(), 1u);
    ASSERT_EQ(raysB.size(), 1u);
    EXPECT_EQ(raysB[0]["scene"], "cornell-spot");
    for (const char* kind : {"coherent", "incoherent"})
        for (const char* key : {"rays", "sameTriangle", "hitFraction"})
            EXPECT_EQ(raysB[0][kind][key], raysA[0][kind][key]) << kind << " " << key;
    EXPECT_NE(text(merged / "report.md").find("GPU ray casting against Embree"), std::string::npos);

    // Run again: every task of the shard is done and skipped, its records untouched.
    const std::string firstId = manifest["tasks"][0]["id"];
    const fs::path firstRecord = shards / "tasks" / (firstId + ".json");
    const auto written = fs::last_write_time(firstRecord);
    const Result again = run(common + " --out " + shards.string() + " --shard 0/2");
    ASSERT_EQ(again.status, 0) << again.output;
    EXPECT_EQ(again.output.find("\ntask "), std::string::npos) << again.output;
    EXPECT_NE(again.output.find("done before: 0\t" + firstId), std::string::npos) << again.output;
    EXPECT_EQ(fs::last_write_time(firstRecord), written);

    // A record of other sources is run again; the others are not. The staging folder a killed run of the
    // task left on this host (its process gone) is removed.
    const fs::path killed =
        shards / "staging" / (firstId + "." + json::parse(text(firstRecord))["host"].get<std::string>() + ".999999999");
    fs::create_directories(killed / "images");
    std::ofstream(killed / "images" / "half.exr") << "half an image";
    json stale = json::parse(text(firstRecord));
    stale["sourceHash"] = "0000000000000000";
    std::ofstream(firstRecord) << stale.dump();
    const Result rerun = run(common + " --out " + shards.string() + " --shard 0/2");
    ASSERT_EQ(rerun.status, 0) << rerun.output;
    EXPECT_NE(rerun.output.find("task 0\t" + firstId), std::string::npos) << rerun.output;
    EXPECT_EQ(json::parse(text(firstRecord))["sourceHash"], manifest["sourceHash"]);
    EXPECT_FALSE(fs::exists(shards / "staging")) << "a killed run's staging folder is removed";
    for (const char* other : {"task 2\t", "task 4\t", "task 6\t"})
        EXPECT_EQ(rerun.output.find(other), std::string::npos) << rerun.output;

    // A task without a record: the merge writes what it has, names the task and fails.
    const json lost = manifest["tasks"][5];
    fs::remove(shards / "tasks" / (lost["id"].get<std::string>() + ".json"));
    const Result partial = run("bench --merge " + shards.string() + " --out " + (d / "partial").string());
    EXPECT_EQ(partial.status, 1) << partial.output;
    EXPECT_NE(partial.output.find(lost["id"].get<std::string>()), std::string::npos) << partial.output;
    const std::string md = text(d / "partial" / "report.md");
    EXPECT_NE(md.find("Incomplete: 1 of 8 tasks"), std::string::npos) << md;
    EXPECT_NE(md.find(lost["id"].get<std::string>()), std::string::npos) << md;
    EXPECT_EQ(json::parse(text(d / "partial" / "results.json")).size(), 3u);
}

// Shards measured on two GL renderers: their times do not compare, so each has its own Pareto front and
// report.md says so.
TEST(BenchShard, MergeOfTwoRenderersDrawsAFrontPerRenderer)
{
    const fs::path d = outDir("renderers");
    const fs::path config = d / "tiny.json";
    std::ofstream(config) << R"({"size": "16x16", "warmup": 0, "frames": 1, "reference": {"spp": 16},
        "scenes": ["cornell-spot"], "runs": [{"technique": "direct"}, {"technique": "rsm"}]})";
    const fs::path shards = d / "shards";
    const Result s = run("bench --backend " + testBackend() + " --config " + config.string() + " --cache " +
                         (d / "cache").string() + " --out " + shards.string() + " --shard 0/1");
    ASSERT_EQ(s.status, 0) << s.output;
    // Both renders: `rsm` made the slower of the two and given another renderer. On one renderer the
    // slower one is on the front only if it is also more accurate; on two, both are on their fronts.
    const json manifest = json::parse(text(shards / "manifest.json"));
    std::vector<fs::path> renders;
    for (const json& t : manifest["tasks"])
        if (t["kind"] == "render") renders.push_back(shards / "tasks" / (t["id"].get<std::string>() + ".json"));
    ASSERT_EQ(renders.size(), 2u);
    json direct = json::parse(text(renders[0])), rsm = json::parse(text(renders[1]));
    rsm["row"]["record"]["imageMs"] = direct["row"]["record"]["imageMs"].get<double>() * 10.0;
    rsm["row"]["record"]["error"]["full"]["relativeRmse"] = 10.0;
    rsm["row"]["relRmseFull"] = 10.0;
    std::ofstream(renders[1]) << rsm.dump();
    Result m = run("bench --merge " + shards.string() + " --out " + (d / "one").string());
    ASSERT_EQ(m.status, 0) << m.output;
    json results = json::parse(text(d / "one" / "results.json"));
    EXPECT_FALSE(results[1]["pareto"]["full"].get<bool>()) << "slower and worse on the same renderer";
    EXPECT_EQ(text(d / "one" / "report.md").find("GL renderers"), std::string::npos);

    rsm["row"]["record"]["renderer"] = "Another GPU/PCIe/SSE2";
    std::ofstream(renders[1]) << rsm.dump();
    m = run("bench --merge " + shards.string() + " --out " + (d / "two").string());
    ASSERT_EQ(m.status, 0) << m.output;
    results = json::parse(text(d / "two" / "results.json"));
    EXPECT_TRUE(results[0]["pareto"]["full"].get<bool>());
    EXPECT_TRUE(results[1]["pareto"]["full"].get<bool>()) << "alone on its renderer's front";
    const std::string md = text(d / "two" / "report.md");
    EXPECT_NE(md.find("Timings from 2 GL renderers"), std::string::npos) << md;
    EXPECT_NE(md.find("Another GPU/PCIe/SSE2"), std::string::npos) << md;
}

// scripts/slurm/submit.sh against a stand-in for sbatch that runs what it is given at once, here: the array's
// tasks one after another with the variables Slurm sets, then the merge. It checks the wiring (the shards
// found from the array, the merge after the array with afterany, both job ids printed, one report in DIR),
// not Slurm itself.
TEST(BenchShard, SlurmSubmitRunsTheArrayThenTheMerge)
{
    const fs::path d = outDir("slurm");
    std::ofstream(d / "tiny.json") << kTinyConfig;
    fs::create_directories(d / "bin");
    const fs::path sbatch = d / "bin" / "sbatch";
    std::ofstream(sbatch) << R"(#!/usr/bin/env bash
# A stand-in for sbatch: runs the job now. Job ids count from 1001 (kept in $SBATCH_STUB_STATE).
set -eu
echo "$*" >> "$SBATCH_STUB_STATE.args"
id=$(( $(cat "$SBATCH_STUB_STATE.id" 2>/dev/null || echo 1000) + 1 )); echo $id > "$SBATCH_STUB_STATE.id"
array="" output="" wrap="" script=""
for a in "$@"; do
  case $a in
    --array=*) array=${a#--array=} ;;
    --output=*) output=${a#--output=} ;;
    --wrap=*) wrap=${a#--wrap=} ;;
    --*) ;;
    *) script=$a ;;
  esac
done
if [ -n "$wrap" ]; then
  bash -c "$wrap" > "${output//%j/$id}" 2>&1 || true
else
  first=${array%-*} last=${array#*-}
  for ((t = first; t <= last; ++t)); do
    log=${output//%A/$id}; log=${log//%a/$t}
    SLURM_ARRAY_JOB_ID=$id SLURM_ARRAY_TASK_ID=$t SLURM_ARRAY_TASK_MIN=$first SLURM_ARRAY_TASK_MAX=$last \
      SLURM_ARRAY_TASK_COUNT=$((last - first + 1)) bash "$script" > "$log" 2>&1 || true
  done
fi
echo "$id"
)";
    fs::permissions(sbatch, fs::perms::owner_all);
    const fs::path dir = d / "study";
    const std::string stub = "PATH=" + (d / "bin").string() + ":$PATH SBATCH_STUB_STATE=" + (d / "sbatch").string();
    const std::string submit = (fs::path(BOUNCE_SOURCE_ROOT) / "scripts/slurm/submit.sh").string();
    const Result r = runShell(stub + " BOUNCE_BIN=" + BOUNCE_BINARY + " BOUNCE_POISON_STORAGE=1 " + submit + " " +
                              (d / "tiny.json").string() + " 3 " + dir.string() + " --backend " + testBackend() +
                              " --cache " + (d / "cache").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("array job 1001"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("merge job 1002"), std::string::npos) << r.output;
    const std::string args = text(d / "sbatch.args");
    EXPECT_NE(args.find("--array=0-2"), std::string::npos) << args;
    EXPECT_NE(args.find("--dependency=afterany:1001"), std::string::npos) << args;
    for (int shard = 0; shard < 3; ++shard) {
        const std::string log = text(dir / "logs" / ("shard-1001_" + std::to_string(shard) + ".log"));
        EXPECT_NE(log.find("shard " + std::to_string(shard) + "/3"), std::string::npos) << log;
    }
    const std::string merge = text(dir / "logs" / "merge-1002.log");
    EXPECT_NE(merge.find("merged 8 of 8 tasks"), std::string::npos) << merge;
    EXPECT_EQ(json::parse(text(dir / "results.json")).size(), 4u);
    EXPECT_TRUE(fs::exists(dir / "report.html"));

    // A bad shard count is refused before anything is queued.
    const Result bad = runShell(stub + " " + submit + " " + (d / "tiny.json").string() + " 0 " + (d / "none").string());
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_FALSE(fs::exists(d / "none"));
}

} // namespace
