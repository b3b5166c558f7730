#include "app/bench_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include <unistd.h>

#include "app/bench_images.h"
#include "app/commands.h"
#include "app/render_job.h"
#include "app/render_sequence.h"
#include "core/image.h"
#include "core/metrics.h"
#include "core/progress.h"
#include "ref/reference.h"

namespace bounce::app {

namespace {

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
                for (int i = std::max(x - 1, 0); i <= std::min(x + 1, width - 1); ++i)
                    mask[std::size_t(j) * width + i] = true;
        }
    return mask;
}

std::string passesText(const nlohmann::json& passes)
{
    std::string text;
    for (const auto& p : passes) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "%s%s=%.3f", text.empty() ? "" : ";", p["pass"].get<std::string>().c_str(),
                      p["medianMs"].get<double>());
        text += buf;
    }
    return text;
}

// What one scene's renders share: its references by light paths and size, its baselines by technique,
// settings and size (e.g. rsm-full at 1024^2: minutes per frame, rendered once per sweep).
struct SceneCache {
    std::map<std::string, core::Image> references, baselines;
    std::map<std::string, double> directLight;  // by frame parameters, size and frame count
    std::map<std::string, std::string> written; // references already in the report's images: key -> id
};

// The emitter mask of a scene seen from its camera at w x h (the `direct` frame's emission channel).
std::vector<bool> emitterMaskOf(const core::Scene& scene, int w, int h)
{
    gl::Renderer d(scene, "direct", gl::ParamValues(gl::frameParams()),
                   gl::ParamValues(gl::findTechnique("direct").params), w, h);
    d.renderFrame(false);
    return emitterMask(d.frame().readEmission(), w, h);
}

// Relative RMSE of the renderer's image against the `full` reference (at the reference's size, emitters
// left out), for the convergence curve.
double errorAgainstFull(const BenchConfig& config, const std::string& sceneName, const core::Scene& scene,
                        gl::Renderer& r, int w, int h, SceneCache& cache)
{
    const int rw = config.reference.width > 0 ? config.reference.width : w;
    const int rh = config.reference.height > 0 ? config.reference.height : h;
    const std::string key = "full@" + std::to_string(rw) + "x" + std::to_string(rh);
    if (!cache.references.count(key))
        cache.references[key] = referenceImage(scene, sceneName, "full", rw, rh, config.reference);
    const std::vector<bool> emitters = emitterMask(r.frame().readEmission(), rw, rh);
    return core::relativeRmse(core::blanked(core::boxDownsample(r.image(), rw, rh), emitters),
                              core::blanked(cache.references[key], emitters));
}

// Error figures against each reference: own light paths, `full`, then compareTo.
void compareWithReferences(const BenchConfig& config, const std::string& sceneName, const core::Scene& scene,
                           gl::Renderer& r, int w, int h, SceneCache& cache, BenchRow& row)
{
    const gl::TechniqueInfo& info = r.technique();
    std::vector<std::string> against = {core::lightPathsName(info.lightPaths), "full"};
    against.insert(against.end(), config.compareTo.begin(), config.compareTo.end());
    // References at their own size (when the config gives one): the image is box-downsampled to it.
    const int rw = config.reference.width > 0 ? config.reference.width : w;
    const int rh = config.reference.height > 0 ? config.reference.height : h;
    core::Image compared;
    std::vector<bool> emitters;
    try {
        emitters = emitterMask(r.frame().readEmission(), rw, rh);
        compared = core::blanked(core::boxDownsample(r.image(), rw, rh), emitters);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("bench config: the reference size must divide every run's size: ") + e.what());
    }
    for (const std::string& paths : against) {
        const std::string key = paths + "@" + std::to_string(rw) + "x" + std::to_string(rh);
        if (!cache.references.count(key))
            cache.references[key] = referenceImage(scene, sceneName, paths, rw, rh, config.reference);
        const core::ImageMetrics m = core::compareImages(compared, core::blanked(cache.references[key], emitters));
        row.record["error"][paths] = {
            {"rmse", m.rmse}, {"relativeRmse", m.relativeRmse}, {"relativeMse", m.relativeMse}, {"mae", m.mae},
            {"ssim", m.ssim}, {"maxError", m.maxError}};
        // Image over reference per channel (R, G, B): the issues' "channel means within N%".
        for (int c = 0; c < 3; ++c)
            row.record["error"][paths]["channelMeanRatio"].push_back(m.channelMeanImage[c] / m.channelMeanReference[c]);
        if (paths == core::lightPathsName(info.lightPaths)) {
            row.relRmseOwn = m.relativeRmse;
            row.rmseOwn = m.rmse;
            row.ssimOwn = m.ssim;
        }
        if (paths == "full") row.relRmseFull = m.relativeRmse;
    }
    for (const std::string& p : config.compareTo)
        row.relRmseCompareTo.push_back(row.record["error"][p]["relativeRmse"].get<double>());
}

// The frame's direct light under the run's frame parameters, rendered as many frames as the run (so with
// the same still frames), against the `direct` reference at the reference's size, emitters left out.
void directLightError(const BenchConfig& config, const std::string& sceneName, const core::Scene& scene,
                      const gl::ParamValues& frameValues, int w, int h, int frames, SceneCache& cache, BenchRow& row)
{
    const int rw = config.reference.width > 0 ? config.reference.width : w;
    const int rh = config.reference.height > 0 ? config.reference.height : h;
    const std::string key =
        frameValues.toJson(gl::frameParams()).dump() + "@" + row.size + "x" + std::to_string(frames);
    if (!cache.directLight.count(key)) {
        gl::Renderer d(scene, "direct", frameValues, gl::ParamValues(gl::findTechnique("direct").params), w, h);
        for (int i = 0; i < frames; ++i) d.renderFrame(false);
        const std::string refKey = "direct@" + std::to_string(rw) + "x" + std::to_string(rh);
        if (!cache.references.count(refKey))
            cache.references[refKey] = referenceImage(scene, sceneName, "direct", rw, rh, config.reference);
        const std::vector<bool> emitters = emitterMask(d.frame().readEmission(), rw, rh);
        cache.directLight[key] = core::relativeRmse(core::blanked(core::boxDownsample(d.image(), rw, rh), emitters),
                                                    core::blanked(cache.references[refKey], emitters));
    }
    row.relRmseDirectLight = cache.directLight[key];
    row.record["error"]["directLight"] = {{"relativeRmse", row.relRmseDirectLight}};
}

// Relative RMSE of the indirect light against the setting's baseline technique: the quantity the two
// gathers compute differently.
void compareWithBaseline(const BenchSetting& s, const core::Scene& scene, gl::Renderer& r, int w, int h,
                         SceneCache& cache, BenchRow& row)
{
    const gl::TechniqueInfo& binfo = gl::findTechnique(s.baseline);
    gl::ParamValues bf(gl::frameParams()), bt(binfo.params);
    applySets(s.baselineSets, binfo, bf, bt);
    const std::string key = s.baseline + " " + settingsText(s.baselineSets) + "@" + row.size;
    if (!cache.baselines.count(key)) {
        gl::Renderer b(scene, s.baseline, bf, bt, w, h);
        b.renderFrame(false);
        cache.baselines[key] = b.frame().read(b.frame().indirect());
    }
    row.relRmseBaseline = core::relativeRmse(r.frame().read(r.frame().indirect()), cache.baselines[key]);
    row.baseline = s.baseline + " " + settingsText(s.baselineSets);
    row.record["baseline"] = {{"technique", s.baseline},
                              {"settings", settingsText(s.baselineSets)},
                              {"relativeRmseIndirect", row.relRmseBaseline}};
}

// The `bounce render` command that makes the same image as a run (same settings, size and frames).
std::string renderCommand(const BenchConfig& config, const BenchSetting& s, const std::string& sceneName)
{
    std::string cmd = "bounce render --scene " + sceneName + " --technique " + s.technique + " --size " +
                      std::to_string(config.widthOf(s)) + "x" + std::to_string(config.heightOf(s)) + " --warmup " +
                      std::to_string(config.warmupOf(s)) + " --frames " + std::to_string(config.framesOf(s));
    for (const std::string& set : s.sets) cmd += " --set " + set;
    return cmd + " --out " + s.technique + ".exr";
}

// The report's name of a cached reference ("full@32x32" of cornell-spot: "ref-cornell-spot-full-32x32").
std::string referenceStem(const std::string& sceneName, const std::string& key)
{
    std::string k = key;
    std::replace(k.begin(), k.end(), '@', '-');
    return "ref-" + sceneName + "-" + k;
}

// Writes the images of the row and every reference of the scene not written yet into out/images/, and
// names them in the row's record: "image" (its own), "references" (by light paths, those at
// referenceSize it was compared with). Nothing when out is empty.
void writeRowImages(const std::filesystem::path& out, const core::Image& image, std::size_t index,
                    const std::string& referenceSize, SceneCache& cache, BenchRow& row)
{
    if (out.empty()) return;
    char stem[256];
    std::snprintf(stem, sizeof stem, "%03zu-%s-%s", index, row.scene.c_str(), row.technique.c_str());
    row.record["image"] = writeReportImage(out, stem, image);
    for (const auto& [key, ref] : cache.references) {
        if (!cache.written.count(key)) cache.written[key] = writeReportImage(out, referenceStem(row.scene, key), ref);
        const std::string paths = key.substr(0, key.find('@'));
        if (key == paths + "@" + referenceSize && row.record["error"].contains(paths))
            row.record["references"][paths] = cache.written[key];
    }
}

} // namespace

// core/metrics.h's rule for images with NaN/Inf, applied to the whole row (flicker and baseline included).
void markNonFinite(BenchRow& row)
{
    const double inf = std::numeric_limits<double>::infinity();
    row.relRmseOwn = row.relRmseFull = row.rmseOwn = inf;
    row.ssimOwn = 0.0;
    for (double& v : row.relRmseCompareTo) v = inf;
    for (auto& [paths, figures] : row.record["error"].items()) {
        if (paths == "directLight") continue; // a render of its own, `direct`'s
        for (auto& [name, value] : figures.items()) value = name == "ssim" ? 0.0 : inf;
    }
    if (!row.baseline.empty()) row.record["baseline"]["relativeRmseIndirect"] = row.relRmseBaseline = inf;
    if (row.record.contains("temporal")) row.record["temporal"]["meanFrameDifference"] = row.flicker = inf;
}

namespace {

BenchRow runSetting(const BenchConfig& config, const BenchSetting& s, const std::string& sceneName,
                    const core::Scene& scene, const gl::ContextInfo& context, SceneCache& cache,
                    const std::filesystem::path& out, std::size_t index)
{
    const int w = config.widthOf(s), h = config.heightOf(s);
    const gl::TechniqueInfo& info = gl::findTechnique(s.technique);
    gl::ParamValues f(gl::frameParams()), t(info.params);
    applySets(s.sets, info, f, t);
    gl::Renderer r(scene, s.technique, f, t, w, h);
    for (int i = 0; i < config.warmupOf(s); ++i) r.renderFrame(false);
    nlohmann::json curve = nlohmann::json::array();
    if (s.curve && info.progressive) r.restartAccumulation();
    double elapsedMs = 0.0;
    for (int i = 0; i < config.framesOf(s); ++i) {
        r.renderFrame(true);
        if (!s.curve) continue;
        for (const gl::PassStat& p : r.timers().lastFrame()) elapsedMs += p.medianMs;
        curve.push_back({{"step", i + 1},
                         {"accumulated", r.accumulatedSteps()},
                         {"elapsedMs", elapsedMs},
                         {"relativeRmseFull", errorAgainstFull(config, sceneName, scene, r, w, h, cache)}});
    }

    BenchRow row;
    row.scene = sceneName;
    row.technique = s.technique;
    row.settings = settingsText(s.sets);
    row.size = std::to_string(w) + "x" + std::to_string(h);
    row.lightPaths = core::lightPathsName(info.lightPaths);
    row.relRmseOwn = row.relRmseFull = row.rmseOwn = row.ssimOwn = row.relRmseBaseline = row.flicker = NAN;
    row.relRmseDirectLight = NAN;
    row.record = runRecord(context, sceneName, r);
    row.record["settings"] = row.settings;
    row.passes = passesText(row.record["passes"]);
    row.totalMs = row.record["totalMs"].get<double>();
    compareWithReferences(config, sceneName, scene, r, w, h, cache, row);
    directLightError(config, sceneName, scene, f, w, h, config.warmupOf(s) + config.framesOf(s), cache, row);
    if (!s.baseline.empty()) compareWithBaseline(s, scene, r, w, h, cache, row);
    if (s.temporalFrames > 0) {
        row.flicker = temporalFlicker(scene, r, s.temporalFrames);
        row.record["temporal"] = {{"frames", s.temporalFrames}, {"meanFrameDifference", row.flicker}};
    }
    row.record["size"] = row.size;
    if (s.curve) row.record["curve"] = curve;
    row.record["command"] = renderCommand(config, s, sceneName);
    const int rw = config.reference.width > 0 ? config.reference.width : w;
    const int rh = config.reference.height > 0 ? config.reference.height : h;
    writeRowImages(out, r.image(), index, std::to_string(rw) + "x" + std::to_string(rh), cache, row);
    row.nonFiniteValues = row.record["nonFiniteValues"].get<std::size_t>();
    if (row.nonFiniteValues > 0) markNonFinite(row);
    return row;
}

// The `bounce render --path` command that renders the same frames as a camera-path run.
std::string pathCommand(const BenchConfig& config, const BenchSetting& s, const std::string& sceneName)
{
    std::string cmd = "bounce render --scene " + sceneName + " --technique " + s.technique + " --path " + s.pathFile +
                      " --size " + std::to_string(config.widthOf(s)) + "x" + std::to_string(config.heightOf(s)) +
                      " --every " + std::to_string(s.every) + " --indirect-scale " + std::to_string(s.indirectScale);
    for (const std::string& set : s.sets) cmd += " --set " + set;
    return cmd + " --out " + s.technique + "-path";
}

// A frame of a camera-path run as compared: the render box-downsampled to the reference's size, its
// reference, and which of their pixels see an emitter.
struct ComparedFrame {
    int frame = -1;
    core::Image image, reference;
    std::vector<bool> emitters;
};

// The emitters of either frame left out of both: the flicker of a pair is taken over the same pixels.
double pairFlicker(const ComparedFrame& a, const ComparedFrame& b)
{
    std::vector<bool> mask = a.emitters;
    for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = mask[i] || b.emitters[i];
    return core::errorFlicker(core::blanked(a.image, mask), core::blanked(a.reference, mask),
                              core::blanked(b.image, mask), core::blanked(b.reference, mask));
}

// A camera-path run (issue 58, "Sequences"): the path rendered one frame per step with no still frames,
// as `bounce render --path` renders it, each frame timed. Frames iK and iK+1 (K = "every") are compared
// with path-tracer references of the technique's own light paths at their own camera and lights (cached
// like every reference), and each pair (iK, iK+1) gives a flicker (core::errorFlicker: the change of the
// error image, so that a stable bias is not called flicker). With "stillFrames" N, frame iK is also
// rendered still, N frames at its camera from a fresh renderer at full resolution, for the ratio of the
// moving frame's error to the still image's. The row's error is the mean over the measured frames.
BenchRow pathRow(const BenchConfig& config, const BenchSetting& s, const std::string& sceneName,
                 const core::Scene& scene, const gl::ContextInfo& context, const std::filesystem::path& out,
                 std::size_t index)
{
    const int w = config.widthOf(s), h = config.heightOf(s);
    const int rw = config.reference.width > 0 ? config.reference.width : w;
    const int rh = config.reference.height > 0 ? config.reference.height : h;
    const gl::TechniqueInfo& info = gl::findTechnique(s.technique);
    gl::ParamValues f(gl::frameParams()), t(info.params);
    applySets(s.sets, info, f, t);
    const core::CameraPath& path = s.path;
    const SceneOnPath onPath = sceneOnPath(scene, path, s.pathFile);
    const std::unique_ptr<gl::Renderer> made =
        makeRendererForCli(onPath.scene, s.technique, f, t, w, h, s.indirectScale);
    gl::Renderer& r = *made;
    const std::string paths = core::lightPathsName(info.lightPaths);
    const auto measured = [&](int frame) { return frame % s.every == 0 || (frame >= 1 && (frame - 1) % s.every == 0); };

    char stem[256];
    std::snprintf(stem, sizeof stem, "%03zu-%s-%s", index, sceneName.c_str(), s.technique.c_str());
    nlohmann::json frames = nlohmann::json::array();
    ComparedFrame previous;
    std::vector<double> errors, secondHalf, flickers, secondHalfFlickers, ratios, stillSecondHalf;
    double sumMs = 0.0;
    std::size_t nonFinite = 0;
    core::Progress progress("path " + s.technique, double(path.frames), "frames");
    for (int fi = 0; fi < path.frames; ++fi) {
        if (fi > 0) stepAlongPath(r, onPath, path, fi);
        r.renderFrame(true);
        double ms = 0.0;
        for (const gl::PassStat& p : r.timers().lastFrame()) ms += p.medianMs;
        sumMs += ms;
        nlohmann::json record = {{"index", fi}, {"ms", ms}};
        if (measured(fi)) {
            const core::Scene at = onPath.at(path, fi);
            ComparedFrame c;
            c.frame = fi;
            c.reference =
                referenceImage(at, sceneName + " frame " + std::to_string(fi), paths, rw, rh, config.reference);
            const core::Image image = r.image();
            nonFinite += nonFiniteValues(image);
            c.emitters = emitterMask(r.frame().readEmission(), rw, rh);
            c.image = core::boxDownsample(image, rw, rh);
            const double e =
                core::relativeRmse(core::blanked(c.image, c.emitters), core::blanked(c.reference, c.emitters));
            record["relativeRmse"] = e;
            errors.push_back(e);
            if (2 * fi >= path.frames) secondHalf.push_back(e);
            if (fi > 0 && (fi - 1) % s.every == 0 && previous.frame == fi - 1) {
                record["flicker"] = pairFlicker(previous, c);
                flickers.push_back(record["flicker"].get<double>());
                // A pair counts for the second half as its error does, by its first frame iK (2 iK >= frames).
                if (2 * (fi - 1) >= path.frames) secondHalfFlickers.push_back(flickers.back());
            }
            if (s.stillFrames > 0 && fi % s.every == 0) {
                gl::Renderer still(at, s.technique, f, t, w, h);
                for (int k = 0; k < s.stillFrames; ++k) still.renderFrame(true);
                const std::vector<bool> m = emitterMask(still.frame().readEmission(), rw, rh);
                const double stillError = core::relativeRmse(
                    core::blanked(core::boxDownsample(still.image(), rw, rh), m), core::blanked(c.reference, m));
                record["stillRelativeRmse"] = stillError;
                ratios.push_back(e / stillError);
                if (2 * fi >= path.frames) stillSecondHalf.push_back(stillError);
            }
            if (!out.empty()) {
                char frameStem[300];
                std::snprintf(frameStem, sizeof frameStem, "%s-f%04d", stem, fi);
                record["image"] = writeReportImage(out, frameStem, image);
                std::snprintf(frameStem, sizeof frameStem, "%s-f%04d-ref-%s", stem, fi, paths.c_str());
                record["reference"] = writeReportImage(out, frameStem, c.reference);
            }
            previous = std::move(c);
        }
        frames.push_back(record);
        progress.add(1.0);
    }
    progress.finish();

    const auto mean = [](const std::vector<double>& v) {
        double sum = 0.0;
        for (double x : v) sum += x;
        return v.empty() ? double(NAN) : sum / double(v.size());
    };
    BenchRow row;
    row.scene = sceneName;
    row.technique = s.technique;
    row.settings = settingsText(s.sets);
    row.size = std::to_string(w) + "x" + std::to_string(h);
    row.lightPaths = paths;
    row.rmseOwn = row.ssimOwn = row.relRmseFull = row.relRmseBaseline = row.relRmseDirectLight = NAN;
    row.relRmseCompareTo.assign(config.compareTo.size(), NAN);
    row.record = runRecord(context, sceneName, r);
    row.record["settings"] = row.settings;
    row.record["size"] = row.size;
    row.passes = passesText(row.record["passes"]);
    // The mean frame over the whole path (runRecord's figure is the median of the last frame's passes).
    row.totalMs = row.record["totalMs"] = sumMs / double(path.frames);
    row.record["imageMs"] = row.totalMs;
    row.record["imageFrames"] = 1;
    row.relRmseOwn = mean(errors);
    row.flicker = mean(flickers);
    row.record["error"][paths] = {{"relativeRmse", row.relRmseOwn}};
    nlohmann::json sequence = {
        {"path", s.pathFile},
        {"frameCount", path.frames},
        {"every", s.every},
        {"indirectScale", s.indirectScale},
        {"stillFrames", s.stillFrames},
        {"meanRelativeRmse", row.relRmseOwn},
        {"secondHalfMeanRelativeRmse", mean(secondHalf)},
        {"worstRelativeRmse", errors.empty() ? double(NAN) : *std::max_element(errors.begin(), errors.end())},
        {"flicker", row.flicker},
        // Without the pairs that follow a history's start (frames 0 and 1: the first blend takes half of
        // each), the figure beside the second half's error.
        {"secondHalfFlicker", mean(secondHalfFlickers)},
        {"meanMs", row.totalMs},
        {"frames", frames}};
    if (!ratios.empty()) {
        sequence["meanStillRatio"] = mean(ratios);
        sequence["worstStillRatio"] = *std::max_element(ratios.begin(), ratios.end());
    }
    // Issue 58's figure: the second half's mean moving error over the mean still error at the second half's
    // frames iK (each still image stands for its pair iK, iK+1).
    if (!stillSecondHalf.empty()) {
        sequence["secondHalfStillRelativeRmse"] = mean(stillSecondHalf);
        sequence["secondHalfStillRatio"] = mean(secondHalf) / mean(stillSecondHalf);
    }
    row.record["sequence"] = sequence;
    row.record["command"] = pathCommand(config, s, sceneName);
    // The report's table and viewer open a run on its last measured frame beside that frame's reference.
    for (auto it = frames.rbegin(); it != frames.rend(); ++it)
        if (it->contains("image")) {
            row.record["image"] = (*it)["image"];
            row.record["references"][paths] = (*it)["reference"];
            break;
        }
    row.record["nonFiniteValues"] = row.nonFiniteValues = nonFinite;
    if (row.nonFiniteValues > 0) markNonFinite(row);
    return row;
}

// The path tracer's own time against error: `full` at `spp` samples per pixel, rendered afresh (never
// cached: the time is the figure), against the scene's reference.
BenchRow pathTracerRow(const BenchConfig& config, const std::string& sceneName, const core::Scene& scene, int spp,
                       SceneCache& cache, const std::filesystem::path& out, std::size_t index)
{
    const int w = config.reference.width > 0 ? config.reference.width : config.width;
    const int h = config.reference.height > 0 ? config.reference.height : config.height;
    const std::string key = "full@" + std::to_string(w) + "x" + std::to_string(h);
    if (!cache.references.count(key))
        cache.references[key] = referenceImage(scene, sceneName, "full", w, h, config.reference);
    ref::RenderSettings rs;
    rs.paths = ref::LightPaths::Full;
    rs.width = w;
    rs.height = h;
    rs.spp = spp;
    rs.seed = 1234; // not the reference's seed: independent noise
    rs.progress = false;
    const ref::RenderResult res = ref::render(scene, scene.camera, rs);
    BenchRow row;
    row.scene = sceneName;
    row.technique = "path-tracer";
    row.settings = "spp=" + std::to_string(spp);
    row.size = std::to_string(w) + "x" + std::to_string(h);
    row.lightPaths = "full";
    row.totalMs = res.seconds * 1000.0;
    const std::vector<bool> emitters = emitterMaskOf(scene, w, h);
    const core::ImageMetrics m =
        core::compareImages(core::blanked(res.image, emitters), core::blanked(cache.references[key], emitters));
    row.relRmseFull = row.relRmseOwn = m.relativeRmse;
    row.rmseOwn = m.rmse;
    row.ssimOwn = m.ssim;
    row.relRmseBaseline = row.flicker = row.relRmseDirectLight = NAN;
    row.relRmseCompareTo.assign(config.compareTo.size(), NAN);
    row.record = {{"scene", sceneName},
                  {"technique", "path-tracer"},
                  {"settings", row.settings},
                  {"size", row.size},
                  {"lightPaths", "full"},
                  {"totalMs", row.totalMs},
                  {"imageFrames", 1},
                  {"imageMs", row.totalMs},
                  {"rays", res.rays},
                  {"spp", spp},
                  {"passes", nlohmann::json::array()},
                  {"error", {{"full", {{"relativeRmse", m.relativeRmse}, {"rmse", m.rmse}, {"ssim", m.ssim}}}}},
                  {"command", "bounce reference --scene " + sceneName + " --paths full --size " + row.size + " --spp " +
                                  std::to_string(spp) + " --seed 1234 --out path-tracer.exr"}};
    writeRowImages(out, res.image, index, row.size, cache, row);
    return row;
}

// Where a row was measured: the machine, and the GL renderer and driver whose timings (and, for the path
// tracer, whose host's CPU) it holds. The report draws a Pareto front per renderer.
void recordMachine(const gl::ContextInfo& context, BenchRow& row)
{
    row.record["host"] = hostName();
    row.record["renderer"] = context.renderer;
    row.record["glVersion"] = context.version;
}

} // namespace

std::vector<BenchRow> runBenchmark(const BenchConfig& config, const gl::ContextInfo& context,
                                   const std::function<void(const std::vector<BenchRow>&)>& afterRow,
                                   const std::filesystem::path& out)
{
    std::size_t renders = 0;
    for (const auto& n : config.sceneNames)
        for (const BenchSetting& s : config.settings) renders += s.runsOn(n);
    core::Progress progress("bench", double(renders), "renders");
    std::vector<BenchRow> rows;
    for (std::size_t si = 0; si < config.scenes.size(); ++si) {
        SceneCache cache;
        for (int spp : config.pathTracerSpp) {
            rows.push_back(
                pathTracerRow(config, config.sceneNames[si], config.scenes[si], spp, cache, out, rows.size()));
            recordMachine(context, rows.back());
        }
        for (const BenchSetting& s : config.settings) {
            if (!s.runsOn(config.sceneNames[si])) continue;
            rows.push_back(s.isPath()
                               ? pathRow(config, s, config.sceneNames[si], config.scenes[si], context, out, rows.size())
                               : runSetting(config, s, config.sceneNames[si], config.scenes[si], context, cache, out,
                                            rows.size()));
            recordMachine(context, rows.back());
            progress.add(1.0);
            if (afterRow) afterRow(rows);
        }
    }
    progress.finish();
    return rows;
}

BenchRow runTaskRow(const BenchConfig& config, const BenchTask& task, const gl::ContextInfo& context,
                    const std::filesystem::path& out)
{
    SceneCache cache;
    const std::string& sceneName = config.sceneNames[task.scene];
    const core::Scene& scene = config.scenes[task.scene];
    BenchRow row;
    if (task.kind == BenchTask::Kind::PathTracer)
        row = pathTracerRow(config, sceneName, scene, task.spp, cache, out, task.row);
    else if (config.settings[task.setting].isPath())
        row = pathRow(config, config.settings[task.setting], sceneName, scene, context, out, task.row);
    else
        row = runSetting(config, config.settings[task.setting], sceneName, scene, context, cache, out, task.row);
    recordMachine(context, row);
    return row;
}

std::string hostName()
{
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
    return name;
}

} // namespace bounce::app
