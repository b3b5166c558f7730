// bounce bench: scenes x techniques x parameter settings, each rendered with timer queries (warm-up
// frames, then the median and spread of the timed frames) and compared with the cached ground truth of
// the technique's own light paths and of `full`. Writes results.csv, results.json, report.md and
// speed_error.png (bench/plot_speed_error.py, matplotlib) into --out.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/bench_reference.h"
#include "app/commands.h"
#include "app/options.h"
#include "app/render_job.h"
#include "core/image.h"
#include "core/metrics.h"
#include "core/progress.h"

namespace bounce::app {

namespace {

namespace fs = std::filesystem;

const char* kUsage =
    "usage: bounce bench --config bench/NAME.json --out DIR [--backend egl|osmesa] [--cache DIR]\n"
    "\n"
    "For each scene x technique x parameter setting of the config: render (warm-up frames, then timed\n"
    "frames: median, min, max GPU ms per pass), compare with the cached references (the technique's own\n"
    "light paths and `full`), and write DIR/results.csv, DIR/results.json, DIR/report.md and\n"
    "DIR/speed_error.png (time against relative RMSE, log scales, Pareto front marked).\n"
    "\n"
    "Config: {\"size\": \"WxH\", \"warmup\": N, \"frames\": N, \"reference\": {\"spp\": N} | {\"noise\": X} [+ \"size\"],\n"
    "         \"scenes\": [...], \"runs\": [{\"technique\": T, \"set\": {k: v}, \"sweep\": {k: [v...]}}]}\n"
    "A sweep is the cartesian product of its lists. A run may also name \"against\": {\"technique\": T,\n"
    "\"set\": {...}} (relative RMSE of the indirect light against it, e.g. full-resolution gathering) and\n"
    "\"temporalFrames\": N (the light moves along a fixed circle; mean frame-to-frame difference of the\n"
    "indirect light). A run may override \"size\", \"warmup\" and \"frames\" and restrict \"scenes\".\n"
    "The top-level \"compareTo\": [paths...] adds references beyond the technique's own and `full` (e.g.\n"
    "\"onebounce\"). A reference \"size\" that divides every run's size compares box-downsampled images\n"
    "against references of that size: less noise for the same cost. Timings compare only within one run.\n";

struct Setting {
    std::string technique;
    std::vector<std::string> sets; // key=value
    // Optional: another technique to measure against (e.g. full-resolution gathering with the same VPLs).
    std::string baseline;
    std::vector<std::string> baselineSets;
    // Optional: frames of a moving light for the temporal-coherence figure (0: none).
    int temporalFrames = 0;
    // Optional: this run's own image size (0: the config's) and scenes (empty: all of the config's).
    int width = 0, height = 0;
    std::vector<std::string> scenes;
    int warmup = -1, frames = -1; // -1: the config's
};

std::string numberText(const nlohmann::json& v)
{
    if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
    if (v.is_number_integer()) return std::to_string(v.get<long long>());
    if (v.is_number()) {
        std::ostringstream s;
        s << v.get<double>();
        return s.str();
    }
    if (v.is_string()) return v.get<std::string>();
    throw UsageError("bench config: parameter values must be numbers, booleans or strings, not " + v.dump());
}

std::vector<Setting> expand(const nlohmann::json& runs)
{
    std::vector<Setting> out;
    for (const auto& run : runs) {
        if (!run.contains("technique") || !run["technique"].is_string())
            throw UsageError("bench config: every run needs a \"technique\" string: " + run.dump());
        std::vector<std::vector<std::string>> combos{{}};
        if (run.contains("set"))
            for (const auto& [k, v] : run["set"].items()) combos[0].push_back(k + "=" + numberText(v));
        if (run.contains("sweep"))
            for (const auto& [k, list] : run["sweep"].items()) {
                if (!list.is_array() || list.empty()) throw UsageError("bench config: sweep \"" + k + "\" needs a non-empty list");
                std::vector<std::vector<std::string>> next;
                for (const auto& c : combos)
                    for (const auto& v : list) {
                        auto n = c;
                        n.push_back(k + "=" + numberText(v));
                        next.push_back(n);
                    }
                combos = next;
            }
        std::string baseline;
        std::vector<std::string> baselineSets;
        if (run.contains("against")) {
            const auto& a = run["against"];
            if (!a.is_object() || !a.contains("technique"))
                throw UsageError("bench config: \"against\" needs {\"technique\": T, \"set\": {...}}");
            baseline = a["technique"].get<std::string>();
            if (a.contains("set"))
                for (const auto& [k, v] : a["set"].items()) baselineSets.push_back(k + "=" + numberText(v));
        }
        const int temporal = run.value("temporalFrames", 0);
        if (temporal < 0 || temporal == 1) throw UsageError("bench config: temporalFrames must be 0 or >= 2");
        int width = 0, height = 0;
        if (run.contains("size")) parseSize(run["size"].get<std::string>(), width, height);
        const auto scenes = run.value("scenes", std::vector<std::string>{});
        const int warmup = run.value("warmup", -1), frames = run.value("frames", -1);
        if (warmup < -1 || frames == 0 || frames < -1) throw UsageError("bench config: a run's warmup >= 0 and frames >= 1");
        for (const auto& c : combos)
            out.push_back({run["technique"].get<std::string>(), c, baseline, baselineSets, temporal, width, height, scenes,
                           warmup, frames});
    }
    return out;
}

// Temporal coherence (Nichols et al. 2009, Fig. 5): the first light moves along a fixed path (a circle
// of radius 3% of the scene's size around its position, in the horizontal plane, one turn over the
// frames); the figure is the mean over consecutive frames of the mean absolute difference of the
// indirect light, divided by the mean indirect light. Lower is steadier.
double temporalFlicker(const core::Scene& scene, gl::Renderer& r, int frames)
{
    if (scene.lights.empty()) return NAN;
    const float radius = 0.03f * glm::length(scene.bounds().extent());
    std::vector<core::Light> lights = scene.lights;
    const glm::vec3 centre = lights[0].position;
    core::Image previous;
    double sumDiff = 0.0, sumMean = 0.0;
    for (int i = 0; i < frames; ++i) {
        const float a = 2.0f * core::kPi * float(i) / float(frames);
        lights[0].position = centre + radius * glm::vec3(std::cos(a), 0.0f, std::sin(a));
        r.frame().setLights(lights);
        r.renderFrame(false);
        core::Image indirect = r.frame().read(r.frame().indirect());
        double mean = 0.0;
        for (float v : indirect.rgb) mean += v;
        mean /= double(std::max<std::size_t>(indirect.rgb.size(), 1));
        if (i > 0) {
            double diff = 0.0;
            for (std::size_t k = 0; k < indirect.rgb.size(); ++k) diff += std::abs(indirect.rgb[k] - previous.rgb[k]);
            sumDiff += diff / double(indirect.rgb.size());
            sumMean += mean;
        }
        previous = std::move(indirect);
    }
    r.frame().setLights(scene.lights);
    return sumMean > 0.0 ? sumDiff / sumMean : 0.0;
}

// Emitters seen directly are left out of the error figures: their radiance is the G-buffer's in every
// technique (exact, tested), and their edges alias against a box-filtered reference (a pixel of an
// emitter of radiance 17 next to a wall of 0.1 is off by up to 17 for coverage alone), which swamped
// every figure on cornell-area. The mask: every reference-size pixel whose block of the render holds an
// emitting pixel, and its 8 neighbours (the reference's partial coverage at the edge).
std::vector<bool> emitterMask(const core::Image& emission, int width, int height)
{
    const core::Image blocks = core::boxDownsample(emission, width, height);
    std::vector<bool> mask(std::size_t(width) * std::size_t(height), false);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec3 e = blocks.at(x, y);
            if (std::max({e.x, e.y, e.z}) <= 0.0f) continue;
            for (int j = std::max(y - 1, 0); j <= std::min(y + 1, height - 1); ++j)
                for (int i = std::max(x - 1, 0); i <= std::min(x + 1, width - 1); ++i) mask[std::size_t(j) * width + i] = true;
        }
    return mask;
}

// Sets the masked pixels to 0 (black: no error there, no weight in the reference's mean).
core::Image blanked(core::Image image, const std::vector<bool>& mask)
{
    for (std::size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) image.rgb[3 * i] = image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = 0.0f;
    return image;
}

std::string joined(const std::vector<std::string>& v, const char* sep)
{
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
    return s.empty() ? "defaults" : s;
}

std::string csvField(const std::string& s)
{
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

} // namespace

int cmdBench(const Args& args)
{
    const Options o(args, {{"config"}, {"out"}, {"backend"}, {"cache"}}, kUsage);
    if (o.helpRequested()) { std::fputs(kUsage, stdout); return 0; }
    if (!o.has("config") || !o.has("out")) throw UsageError("--config and --out are required\n\n" + std::string(kUsage));
    nlohmann::json config;
    {
        std::ifstream in(o.get("config"));
        if (!in) throw UsageError("cannot read bench config '" + o.get("config") + "'");
        try { config = nlohmann::json::parse(in); } catch (const std::exception& e) {
            throw UsageError("bench config '" + o.get("config") + "': " + e.what());
        }
    }
    int width = 128, height = 128;
    parseSize(config.value("size", std::string("128x128")), width, height);
    const int warmup = config.value("warmup", 2), frames = config.value("frames", 5);
    if (warmup < 0 || frames < 1) throw UsageError("bench config: warmup >= 0 and frames >= 1");
    const std::vector<Setting> settings = expand(config.value("runs", nlohmann::json::array()));
    const auto sceneNames = config.value("scenes", std::vector<std::string>{"cornell-spot"});
    const auto compareTo = config.value("compareTo", std::vector<std::string>{});
    for (const Setting& s : settings)
        for (const std::string& n : s.scenes)
            if (std::find(sceneNames.begin(), sceneNames.end(), n) == sceneNames.end())
                throw UsageError("bench config: a run names scene '" + n + "', which is not in \"scenes\"");
    // Check every technique and parameter before the first (long) render.
    for (const Setting& s : settings) {
        const gl::TechniqueInfo* info = nullptr;
        try { info = &gl::findTechnique(s.technique); } catch (const std::invalid_argument& e) { throw UsageError(e.what()); }
        gl::ParamValues f(gl::frameParams()), t(info->params);
        applySets(s.sets, *info, f, t);
        if (!s.baseline.empty()) {
            try { info = &gl::findTechnique(s.baseline); } catch (const std::invalid_argument& e) { throw UsageError(e.what()); }
            gl::ParamValues bf(gl::frameParams()), bt(info->params);
            applySets(s.baselineSets, *info, bf, bt);
        }
    }
    std::vector<core::Scene> scenes;
    for (const auto& n : sceneNames) scenes.push_back(loadSceneForCli(n));
    const ReferenceSpec refSpec = referenceSpecFrom(config.value("reference", nlohmann::json::object()), o.get("cache"));
    for (const Setting& s : settings) {
        const int w = s.width > 0 ? s.width : width, h = s.height > 0 ? s.height : height;
        if ((refSpec.width > 0 && w % refSpec.width != 0) || (refSpec.height > 0 && h % refSpec.height != 0))
            throw UsageError("bench config: the reference size " + std::to_string(refSpec.width) + "x" +
                             std::to_string(refSpec.height) + " does not divide the run size " + std::to_string(w) + "x" +
                             std::to_string(h) + " (" + s.technique + ")");
    }

    const fs::path out = o.get("out");
    fs::create_directories(out);
    auto context = createContextForCli(o.get("backend", "egl"));
    std::printf("GL renderer: %s (%s)\n", context->info().renderer.c_str(), context->info().platform.c_str());

    nlohmann::json results = nlohmann::json::array();
    std::ostringstream csv;
    csv << "scene,technique,params,size,light_paths,total_ms,rel_rmse_own,rel_rmse_full,rmse_own,ssim_own,baseline,"
           "rel_rmse_baseline,flicker,passes";
    for (const std::string& p : compareTo) csv << ",rel_rmse_" << p;
    csv << "\n";
    const auto runsOn = [](const Setting& s, const std::string& scene) {
        return s.scenes.empty() || std::find(s.scenes.begin(), s.scenes.end(), scene) != s.scenes.end();
    };
    std::size_t renders = 0;
    for (const auto& n : sceneNames)
        for (const Setting& s : settings) renders += runsOn(s, n);
    core::Progress progress("bench", double(renders), "renders");
    for (std::size_t si = 0; si < scenes.size(); ++si) {
        const core::Scene& scene = scenes[si];
        // Reference images (cached on disk too) and baseline renders, by light paths or technique + size.
        std::map<std::string, core::Image> refs, baselines;
        for (const Setting& s : settings) {
            if (!runsOn(s, sceneNames[si])) continue;
            const int w = s.width > 0 ? s.width : width, h = s.height > 0 ? s.height : height;
            const std::string sizeText = std::to_string(w) + "x" + std::to_string(h);
            const gl::TechniqueInfo& info = gl::findTechnique(s.technique);
            gl::ParamValues f(gl::frameParams()), t(info.params);
            applySets(s.sets, info, f, t);
            gl::Renderer r(scene, s.technique, f, t, w, h);
            for (int i = 0; i < (s.warmup >= 0 ? s.warmup : warmup); ++i) r.renderFrame(false);
            for (int i = 0; i < (s.frames > 0 ? s.frames : frames); ++i) r.renderFrame(true);
            const core::Image image = r.image();
            nlohmann::json rec = runRecord(context->info(), sceneNames[si], r);
            rec["settings"] = joined(s.sets, " ");
            std::string passText;
            for (const auto& p : rec["passes"]) {
                char buf[96];
                std::snprintf(buf, sizeof buf, "%s%s=%.3f", passText.empty() ? "" : ";", p["pass"].get<std::string>().c_str(),
                              p["medianMs"].get<double>());
                passText += buf;
            }
            double relOwn = NAN, relFull = NAN, rmseOwn = NAN, ssimOwn = NAN;
            std::vector<std::string> against = {core::lightPathsName(info.lightPaths), "full"};
            against.insert(against.end(), compareTo.begin(), compareTo.end());
            // References at their own size (when the config gives one): the image is box-downsampled to it.
            const int rw = refSpec.width > 0 ? refSpec.width : w, rh = refSpec.height > 0 ? refSpec.height : h;
            core::Image compared;
            std::vector<bool> emitters;
            try {
                emitters = emitterMask(r.frame().read(r.frame().emission()), rw, rh);
                compared = blanked(core::boxDownsample(image, rw, rh), emitters);
            } catch (const std::invalid_argument& e) {
                throw UsageError(std::string("bench config: the reference size must divide every run's size: ") + e.what());
            }
            for (const std::string& paths : against) {
                const std::string key = paths + "@" + std::to_string(rw) + "x" + std::to_string(rh);
                if (!refs.count(key)) refs[key] = referenceImage(scene, sceneNames[si], paths, rw, rh, refSpec);
                const core::ImageMetrics m = core::compareImages(compared, blanked(refs[key], emitters));
                rec["error"][paths] = {{"rmse", m.rmse}, {"relativeRmse", m.relativeRmse}, {"relativeMse", m.relativeMse},
                                       {"mae", m.mae}, {"ssim", m.ssim}, {"maxError", m.maxError}};
                if (paths == core::lightPathsName(info.lightPaths)) { relOwn = m.relativeRmse; rmseOwn = m.rmse; ssimOwn = m.ssim; }
                if (paths == "full") relFull = m.relativeRmse;
            }
            double relBaseline = NAN, flicker = NAN;
            if (!s.baseline.empty()) {
                const gl::TechniqueInfo& binfo = gl::findTechnique(s.baseline);
                gl::ParamValues bf(gl::frameParams()), bt(binfo.params);
                applySets(s.baselineSets, binfo, bf, bt);
                const std::string key = s.baseline + " " + joined(s.baselineSets, " ") + "@" + sizeText;
                if (!baselines.count(key)) { // e.g. rsm-full at 1024^2: minutes per frame, rendered once per sweep
                    gl::Renderer b(scene, s.baseline, bf, bt, w, h);
                    b.renderFrame(false);
                    baselines[key] = b.frame().read(b.frame().indirect());
                }
                // Indirect light only: the quantity the two gathers compute differently.
                relBaseline = core::relativeRmse(r.frame().read(r.frame().indirect()), baselines[key]);
                rec["baseline"] = {{"technique", s.baseline}, {"settings", joined(s.baselineSets, " ")},
                                   {"relativeRmseIndirect", relBaseline}};
            }
            if (s.temporalFrames > 0) {
                flicker = temporalFlicker(scene, r, s.temporalFrames);
                rec["temporal"] = {{"frames", s.temporalFrames}, {"meanFrameDifference", flicker}};
            }
            rec["size"] = sizeText;
            results.push_back(rec);
            csv << csvField(sceneNames[si]) << "," << s.technique << "," << csvField(joined(s.sets, " ")) << ","
                << sizeText << "," << core::lightPathsName(info.lightPaths) << "," << rec["totalMs"].get<double>() << "," << relOwn << "," << relFull << ","
                << rmseOwn << "," << ssimOwn << "," << csvField(s.baseline.empty() ? "" : s.baseline + " " + joined(s.baselineSets, " "))
                << "," << relBaseline << "," << flicker << "," << csvField(passText);
            for (const std::string& p : compareTo) csv << "," << rec["error"][p]["relativeRmse"].get<double>();
            csv << "\n";
            progress.add(1.0);
        }
    }
    progress.finish();

    core::writeFileAtomic((out / "results.csv").string(), csv.str());
    core::writeFileAtomic((out / "results.json").string(), results.dump(2) + "\n");

    // report.md: one table per scene, then the per-pass breakdown like the papers' tables.
    std::ostringstream md;
    md << "# Bounce benchmark\n\nGL renderer: " << context->info().renderer << " (" << context->info().platform
       << "). " << width << "x" << height << " unless a row says otherwise, " << warmup << " warm-up + " << frames
       << " timed frames (median GPU ms). Timings compare only within this run. Errors leave out the pixels that see"
          " an emitter directly (and a one-pixel margin): emission is the same exact G-buffer value in every"
          " technique, and its edges alias against the box-filtered references.\n\n";
    for (const auto& sceneName : sceneNames) {
        md << "## " << sceneName << "\n\n| technique | parameters | size | light paths | ms | rel. RMSE (own) | rel. RMSE (full) |";
        for (const std::string& p : compareTo) md << " rel. RMSE (" << p << ") |";
        md << " SSIM (own) | rel. RMSE vs baseline (indirect) | flicker |\n|---|---|---|---|---:|---:|---:|";
        for (std::size_t i = 0; i < compareTo.size(); ++i) md << "---:|";
        md << "---:|---|---:|\n";
        for (const auto& rec : results) {
            if (rec["scene"] != sceneName) continue;
            const std::string lp = rec["lightPaths"];
            char buf[512];
            std::string baseline = "-", flicker = "-";
            if (rec.contains("baseline")) {
                std::snprintf(buf, sizeof buf, "%.4f vs %s (%s)", rec["baseline"]["relativeRmseIndirect"].get<double>(),
                              rec["baseline"]["technique"].get<std::string>().c_str(),
                              rec["baseline"]["settings"].get<std::string>().c_str());
                baseline = buf;
            }
            if (rec.contains("temporal")) {
                std::snprintf(buf, sizeof buf, "%.4f", rec["temporal"]["meanFrameDifference"].get<double>());
                flicker = buf;
            }
            std::snprintf(buf, sizeof buf, "| %s | %s | %s | %s | %.3f | %.4f | %.4f |",
                          rec["technique"].get<std::string>().c_str(), rec["settings"].get<std::string>().c_str(),
                          rec["size"].get<std::string>().c_str(), lp.c_str(), rec["totalMs"].get<double>(),
                          rec["error"][lp]["relativeRmse"].get<double>(), rec["error"]["full"]["relativeRmse"].get<double>());
            md << buf;
            for (const std::string& p : compareTo) {
                std::snprintf(buf, sizeof buf, " %.4f |", rec["error"][p]["relativeRmse"].get<double>());
                md << buf;
            }
            std::snprintf(buf, sizeof buf, " %.4f | %s | %s |\n", rec["error"][lp]["ssim"].get<double>(), baseline.c_str(),
                          flicker.c_str());
            md << buf;
        }
        md << "\n### per-pass GPU ms\n\n";
        std::vector<std::string> passes;
        for (const auto& rec : results)
            if (rec["scene"] == sceneName)
                for (const auto& p : rec["passes"])
                    if (std::find(passes.begin(), passes.end(), p["pass"].get<std::string>()) == passes.end())
                        passes.push_back(p["pass"]);
        md << "| pass |";
        for (const auto& rec : results)
            if (rec["scene"] == sceneName) md << " " << rec["technique"].get<std::string>() << " (" << rec["settings"].get<std::string>() << ") |";
        md << "\n|---|";
        for (const auto& rec : results)
            if (rec["scene"] == sceneName) md << "---:|";
        md << "\n";
        for (const auto& pass : passes) {
            md << "| " << pass << " |";
            for (const auto& rec : results) {
                if (rec["scene"] != sceneName) continue;
                std::string cell = " - |";
                for (const auto& p : rec["passes"])
                    if (p["pass"] == pass) {
                        char buf[64];
                        std::snprintf(buf, sizeof buf, " %.3f |", p["medianMs"].get<double>());
                        cell = buf;
                    }
                md << cell;
            }
            md << "\n";
        }
        md << "\n";
    }
    md << "![speed against error](speed_error.png)\n";
    core::writeFileAtomic((out / "report.md").string(), md.str());

    const std::string plot = "/usr/bin/python3 '" + (fs::path(BOUNCE_SOURCE_ROOT) / "bench/plot_speed_error.py").string() +
                             "' '" + (out / "results.csv").string() + "' '" + (out / "speed_error.png").string() + "'";
    const int rc = std::system(plot.c_str());
    if (rc != 0) std::fprintf(stderr, "bounce bench: the plot script failed (%d): %s\n", rc, plot.c_str());
    std::printf("wrote %s/{results.csv,results.json,report.md,speed_error.png}\n", out.string().c_str());
    return rc == 0 ? 0 : 1;
}

} // namespace bounce::app
