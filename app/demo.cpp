#include "app/demo.h"

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "app/render_job.h"
#include "core/metrics.h"
#include "gl/gl.h"

namespace bounce::app {

namespace {

// The label on its own line above a full-width widget: parameter names such as lightDepthThreshold stay
// whole in a narrow panel instead of being clipped by the label column. Returns the widget's hidden id.
std::string labelAbove(const std::string& label)
{
    ImGui::TextUnformatted(label.c_str());
    ImGui::SetNextItemWidth(-FLT_MIN);
    return "##" + label;
}

// Parameter widgets generated from the declaration; returns true when a value changed.
bool paramWidgets(const std::vector<gl::ParamDecl>& decls, gl::ParamValues& values)
{
    bool changed = false;
    for (const gl::ParamDecl& d : decls) {
        const double v = values.get(d.name);
        if (d.allowAuto) {
            // "auto" is a mode, not a number: a checkbox in front of the number.
            bool automatic = v == gl::kAutoValue;
            if (ImGui::Checkbox(("auto##" + d.name).c_str(), &automatic)) {
                values.setValue(d.name, automatic ? gl::kAutoValue : d.min);
                changed = true;
            }
            ImGui::SameLine();
            if (automatic) {
                ImGui::TextUnformatted(d.name.c_str());
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", d.meaning.c_str());
                continue;
            }
        }
        if (d.type == gl::ParamType::Choice) {
            const std::string id = labelAbove(d.name);
            const std::string current = d.text(v);
            if (ImGui::BeginCombo(id.c_str(), current.c_str())) {
                for (std::size_t i = 0; i < d.choices.size(); ++i)
                    if (ImGui::Selectable(d.choices[i].c_str(), std::size_t(v) == i)) {
                        values.setValue(d.name, double(i));
                        changed = true;
                    }
                ImGui::EndCombo();
            }
        } else if (d.type == gl::ParamType::Bool) {
            bool b = v != 0.0;
            if (ImGui::Checkbox(d.name.c_str(), &b)) {
                values.setValue(d.name, b ? 1.0 : 0.0);
                changed = true;
            }
        } else if (d.type == gl::ParamType::Int) {
            int i = int(v);
            const std::string id = labelAbove(d.name);
            if (ImGui::DragInt(id.c_str(), &i, 1.0f, int(d.min), int(d.max), "%d", ImGuiSliderFlags_AlwaysClamp)) {
                values.setValue(d.name, i);
                changed = true;
            }
        } else {
            float f = float(v);
            const float speed = float((d.max - d.min) / 500.0);
            const std::string id = labelAbove(d.name);
            if (ImGui::DragFloat(id.c_str(), &f, speed, float(d.min), float(d.max), "%.4g",
                                 ImGuiSliderFlags_AlwaysClamp)) {
                values.setValue(d.name, f);
                changed = true;
            }
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", d.meaning.c_str());
    }
    return changed;
}

// A technique chooser; returns true and sets `name` when another one was picked.
bool techniqueCombo(const char* label, std::string& name)
{
    bool picked = false;
    const std::string id = labelAbove(label);
    if (ImGui::BeginCombo(id.c_str(), name.c_str())) {
        for (const gl::TechniqueInfo& t : gl::techniques())
            if (ImGui::Selectable(t.name.c_str(), t.name == name) && t.name != name) {
                name = t.name;
                picked = true;
            }
        ImGui::EndCombo();
    }
    return picked;
}

void saveImage(const core::Image& image, std::filesystem::path path)
{
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    path.replace_extension(".exr");
    core::writeExr(path.string(), image);
    path.replace_extension(".png");
    core::writePng(path.string(), image);
    std::printf("screenshot: %s (+ .exr)\n", path.string().c_str());
}

} // namespace

Demo::Demo(gl::Context& context, DemoSettings settings)
    : context_(context),
      window_(context.window()),
      s_(std::move(settings)),
      fly_(s_.scene.camera),
      lights_(s_.scene.lights)
{
    compareReference_ = !s_.reference.rgb.empty();
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
    // The render resolution follows the window (half of it in side-by-side mode).
    glfwGetFramebufferSize(window_, &viewW_, &viewH_);
    viewW_ = std::max(viewW_, 1);
    viewH_ = std::max(viewH_, 1);
    left_ = makeRenderer(s_.technique, s_.techniqueValues);
    rightValues_ = gl::ParamValues(gl::findTechnique(rightName_).params);
}

Demo::~Demo()
{
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

int Demo::run()
{
    double last = glfwGetTime();
    const double start = last;
    // frame_ms: since the last frame; render_ms: the renderers alone (cmd_demo.cpp's --help)
    if (!s_.frameLog.empty())
        frameLog_ = "seconds,frame_ms,render_ms,indirect_scale,direct_samples,moving,technique,passes\n";
    while (!glfwWindowShouldClose(window_)) {
        glfwPollEvents();
        const double now = glfwGetTime();
        const float dt = float(now - last);
        last = now;
        if (!s_.frameLog.empty() && now > start) {
            char row[256];
            std::snprintf(row, sizeof row, "%.4f,%.3f,%.3f,%d,%d,%d,%s,", now - start, 1e3 * double(dt), frameMs_,
                          budget_.indirectScale, left_->frame().settings().movingDirectSamples, movingForLog_ ? 1 : 0,
                          s_.technique.c_str());
            frameLog_ += row;
            std::string passes; // the left renderer's passes of the frame before: name=ms;...
            for (const gl::PassStat& p : left_->timers().lastFrame()) {
                std::snprintf(row, sizeof row, "%s%s=%.3f", passes.empty() ? "" : ";", p.pass.c_str(), p.medianMs);
                passes += row;
            }
            frameLog_ += passes + "\n";
        }
        if (!runScript()) break;
        if (waitFrames_ > 0) --waitFrames_;
        int fbw = 0, fbh = 0;
        glfwGetFramebufferSize(window_, &fbw, &fbh);
        if (fbw <= 0 || fbh <= 0) continue;

        // The panel first: what it changes (a rebuild, a comparison) is rendered in this very frame.
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        panel();
        renderViews(fbw, fbh, dt);
        halfLabels(fbw);
        ImGui::Render();
        present(fbw, fbh);
        context_.swapBuffers();
    }
    if (!s_.frameLog.empty()) core::writeFileAtomic(s_.frameLog, frameLog_);
    return 0;
}

bool Demo::runScript()
{
    while (waitFrames_ == 0 && !s_.script.empty()) {
        const DemoStep step = s_.script.front();
        s_.script.erase(s_.script.begin());
        if (step.verb == "wait")
            waitFrames_ = std::max(1, std::stoi(step.arg));
        else if (step.verb == "technique")
            setTechnique(step.arg);
        else if (step.verb == "set")
            applySet(step.arg);
        else if (step.verb == "compare")
            compareWith(step.arg);
        else if (step.verb == "screenshot")
            screenshot(step.arg);
        else if (step.verb == "move")
            moveFrames_ = std::stoi(step.arg);
        else if (step.verb == "budget")
            budgetMs_ = float(std::stoi(step.arg));
        else if (step.verb == "quit")
            return false;
    }
    return true;
}

std::unique_ptr<gl::Renderer> Demo::makeRenderer(const std::string& name, const gl::ParamValues& values)
{
    auto r = std::make_unique<gl::Renderer>(s_.scene, name, s_.frameValues, values, viewW_, viewH_);
    r->frame().setLights(lights_);
    r->frame().setCamera(fly_.camera());
    applyBudgetTo(*r);
    return r;
}

void Demo::applyBudgetTo(gl::Renderer& r) const
{
    r.setIndirectScale(budget_.indirectScale);
    if (s_.budgetDirectSamples) r.frame().setMovingDirectSamples(budget_.directSamples);
}

void Demo::setTechnique(const std::string& name)
{
    const gl::TechniqueInfo& t = gl::findTechnique(name);
    s_.technique = t.name;
    s_.techniqueValues = gl::ParamValues(t.params);
    left_->setTechnique(s_.technique, s_.techniqueValues);
}

void Demo::compareWith(const std::string& name)
{
    if (name.empty()) {
        right_.reset();
        return;
    }
    rightName_ = gl::findTechnique(name).name;
    rightValues_ = gl::ParamValues(gl::findTechnique(name).params);
    right_ = makeRenderer(rightName_, rightValues_);
}

void Demo::applySet(const std::string& keyValue)
{
    applySets({keyValue}, left_->technique(), s_.frameValues, s_.techniqueValues);
    if (keyValue.substr(0, keyValue.find('=')) == "moving.directSamples") s_.budgetDirectSamples = false;
    if (isFrameParam(keyValue.substr(0, keyValue.find('='))))
        rebuildRenderers();
    else
        left_->setTechniqueValues(s_.techniqueValues);
}

void Demo::rebuildRenderers()
{
    left_ = makeRenderer(s_.technique, s_.techniqueValues);
    if (right_) right_ = makeRenderer(rightName_, rightValues_);
}

void Demo::screenshot(const std::string& path)
{
    const core::Image left = left_->image();
    saveImage(left, path);
    if (!right_) return;
    // The right half beside it (FILE-right.exr/.png) and the figure its label shows.
    std::filesystem::path p(path);
    p.replace_filename(p.stem().string() + "-right" + p.extension().string());
    const core::Image right = right_->image();
    saveImage(right, p);
    std::printf("relative RMSE of %s (right) against %s (left): %.6g\n", rightName_.c_str(), s_.technique.c_str(),
                core::relativeRmse(right, left));
}

void Demo::renderViews(int fbw, int fbh, float dt)
{
    viewW_ = right_ ? std::max(1, fbw / 2) : fbw;
    viewH_ = fbh;
    movedThisFrame_ |= fly_.update(window_, dt, speed_);
    if (moveFrames_ > 0) {
        fly_.strafe(0.01f);
        --moveFrames_;
        movedThisFrame_ = true;
    }
    applyBudget(glfwGetTime());
    const auto start = std::chrono::steady_clock::now();
    for (gl::Renderer* r : {left_.get(), right_.get()}) {
        if (!r) continue;
        r->frame().resize(viewW_, viewH_);
        r->frame().setCamera(fly_.camera());
        r->renderFrame();
    }
    glFinish();
    frameMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    referenceRelRmse_ = halvesRelRmse_ = -1.0;
    const bool withReference = compareReference_ && s_.reference.width == viewW_ && s_.reference.height == viewH_;
    if (!withReference && !right_) return;
    const core::Image left = left_->image();
    if (withReference) {
        referenceRelRmse_ = core::relativeRmse(left, s_.reference);
        if (showHeatmap_) DemoView::upload(core::errorHeatmap(left, s_.reference), heatmap_);
    }
    if (right_) halvesRelRmse_ = core::relativeRmse(right_->image(), left);
}

void Demo::applyBudget(double now)
{
    if (movedThisFrame_) lastMoveTime_ = now;
    movedThisFrame_ = false;
    const bool moving = now - lastMoveTime_ < kStillSeconds;
    movingForLog_ = moving;
    // A technique drawn at full resolution at every scale (gl::Renderer::indirectScales) gains nothing from it.
    const bool scales = left_->indirectScales() || (right_ && right_->indirectScales());
    const FrameBudgetState next =
        budgetOn_ ? nextFrameBudget(budget_, moving, frameMs_, double(budgetMs_), scales, s_.budgetDirectSamples)
                  : FrameBudgetState{1, s_.frameValues.getInt("moving.directSamples")};
    const bool points = next.directSamples != budget_.directSamples;
    const bool rescaled = next.indirectScale != budget_.indirectScale;
    if (!points && !rescaled) return;
    budget_ = next;
    for (gl::Renderer* r : {left_.get(), right_.get()})
        if (r) applyBudgetTo(*r);
    if (points)
        std::printf("budget: %d points of the direct light per moving frame, %.0f ms against a %.0f ms budget\n",
                    budget_.directSamples, frameMs_, double(budgetMs_));
    const int scale = budget_.indirectScale;
    if (rescaled && scale == 1)
        std::printf("budget: full resolution (still)\n");
    else if (rescaled)
        std::printf("budget: indirect light at 1/%d resolution (%dx%d) while moving, %.0f ms over a %.0f ms budget\n",
                    scale, left_->indirectWidth(), left_->indirectHeight(), frameMs_, double(budgetMs_));
    std::fflush(stdout);
}

void Demo::panel()
{
    ImGui::SetNextWindowPos(ImVec2(8, 32), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(320, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("Bounce");
    ImGui::TextWrapped("%s", context_.info().renderer.c_str());
    std::string id;
    std::string name = s_.technique;
    if (techniqueCombo(right_ ? "technique (left)" : "technique", name)) setTechnique(name);
    ImGui::TextWrapped("%s", left_->technique().summary.c_str());
    // Uniform parameters reach the running technique without a rebuild (no shader is recompiled).
    if (paramWidgets(left_->technique().params, s_.techniqueValues)) left_->setTechniqueValues(s_.techniqueValues);
    if (ImGui::CollapsingHeader("frame")) {
        const int points = s_.frameValues.getInt("moving.directSamples");
        if (paramWidgets(gl::frameParams(), s_.frameValues)) {
            // The panel's moving.directSamples, once changed, is the user's: the budget leaves it.
            if (s_.frameValues.getInt("moving.directSamples") != points) s_.budgetDirectSamples = false;
            rebuildRenderers();
        }
    }
    if (!lights_.empty() && ImGui::CollapsingHeader("light", ImGuiTreeNodeFlags_DefaultOpen)) {
        core::Light& l = lights_[0];
        std::string id = labelAbove("position");
        bool moved = ImGui::DragFloat3(id.c_str(), &l.position.x, 0.005f);
        float yaw = std::atan2(l.direction.x, l.direction.z), pitch = std::asin(glm::clamp(l.direction.y, -1.f, 1.f));
        id = labelAbove("yaw");
        bool turned = ImGui::DragFloat(id.c_str(), &yaw, 0.01f);
        id = labelAbove("pitch");
        turned |= ImGui::DragFloat(id.c_str(), &pitch, 0.01f, -1.57f, 1.57f);
        if (turned) l.direction = {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
        if (moved || turned) {
            movedThisFrame_ = true; // the frame budget treats a moving light as a moving camera
            for (gl::Renderer* r : {left_.get(), right_.get()})
                if (r) r->frame().setLights(lights_);
        }
    }
    id = labelAbove("exposure (stops)");
    ImGui::DragFloat(id.c_str(), &exposure_, 0.05f, -10.f, 10.f);
    id = labelAbove("move speed (m/s)");
    ImGui::DragFloat(id.c_str(), &speed_, 0.01f, 0.01f, 100.f);
    if (ImGui::CollapsingHeader("frame budget", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Text("%.1f frames/s (%.0f ms)", frameMs_ > 0 ? 1000.0 / frameMs_ : 0.0, frameMs_);
        ImGui::Checkbox("coarser indirect light (or more direct points) while moving", &budgetOn_);
        id = labelAbove("budget (ms)");
        ImGui::DragFloat(id.c_str(), &budgetMs_, 1.0f, 1.0f, 10000.0f, "%.0f");
        ImGui::Text("indirect light: %dx%d (1/%d)", left_->indirectWidth(), left_->indirectHeight(),
                    budget_.indirectScale);
        ImGui::Text("direct light: %d points per moving frame", left_->frame().settings().movingDirectSamples);
    }
    if (ImGui::CollapsingHeader("passes (GPU ms)", ImGuiTreeNodeFlags_DefaultOpen)) {
        double total = 0;
        const std::vector<gl::PassStat> passes = left_->timers().lastFrame();
        for (const gl::PassStat& p : passes) total += p.medianMs;
        for (const gl::PassStat& p : passes) {
            // One bar per pass, its share of the frame.
            char text[96];
            std::snprintf(text, sizeof text, "%s %.2f ms", p.pass.c_str(), p.medianMs);
            ImGui::ProgressBar(total > 0 ? float(p.medianMs / total) : 0.0f, ImVec2(-FLT_MIN, 0), text);
        }
        ImGui::Text("%-24s %8.3f", "total", total);
        for (const gl::Counter& c : left_->counters()) ImGui::Text("%-24s %g", c.name.c_str(), c.value);
    }
    comparePanel();
    if (ImGui::Button("screenshot (F12)") || ImGui::IsKeyPressed(GLFW_KEY_F12, false))
        screenshot("out/screenshot-" + std::to_string(shot_++) + ".exr");
    ImGui::End();
}

void Demo::comparePanel()
{
    if (!ImGui::CollapsingHeader("compare")) return;
    bool sideBySide = bool(right_);
    if (ImGui::Checkbox("side by side", &sideBySide)) compareWith(sideBySide ? rightName_ : "");
    if (right_) {
        ImGui::PushID("right");
        std::string name = rightName_;
        if (techniqueCombo("technique (right)", name)) compareWith(name);
        if (paramWidgets(right_->technique().params, rightValues_)) right_->setTechniqueValues(rightValues_);
        if (halvesRelRmse_ >= 0) ImGui::Text("relative RMSE, right against left: %.4f", halvesRelRmse_);
        ImGui::PopID();
    }
    if (!s_.reference.rgb.empty()) {
        ImGui::Checkbox("left against the reference", &compareReference_);
        ImGui::Checkbox("heat map", &showHeatmap_);
        if (referenceRelRmse_ >= 0)
            ImGui::Text("relative RMSE %.4f", referenceRelRmse_);
        else if (compareReference_)
            ImGui::Text("reference is %dx%d; view is %dx%d", s_.reference.width, s_.reference.height, viewW_, viewH_);
    }
}

// Each half says what it shows: the technique, and the relative RMSE of the right against the left (or
// of the left against the reference).
void Demo::halfLabels(int fbw)
{
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float scale = ImGui::GetIO().DisplaySize.x / float(std::max(fbw, 1)); // framebuffer -> ImGui units
    const auto label = [&](float x, const std::string& text) {
        const ImVec2 at(x + 6.0f, 6.0f), size = ImGui::CalcTextSize(text.c_str());
        draw->AddRectFilled(ImVec2(at.x - 3, at.y - 2), ImVec2(at.x + size.x + 3, at.y + size.y + 2),
                            IM_COL32(0, 0, 0, 170));
        draw->AddText(at, IM_COL32(255, 255, 255, 255), text.c_str());
    };
    char buf[160];
    std::string left = s_.technique;
    if (referenceRelRmse_ >= 0) {
        std::snprintf(buf, sizeof buf, "  rel. RMSE %.4f against the reference%s", referenceRelRmse_,
                      showHeatmap_ ? " (heat map)" : "");
        left += buf;
    }
    label(0.0f, left);
    if (!right_) return;
    std::snprintf(buf, sizeof buf, "  rel. RMSE %.4f against the left", halvesRelRmse_);
    label(float(viewW_) * scale, rightName_ + (halvesRelRmse_ >= 0 ? buf : ""));
}

void Demo::present(int fbw, int fbh)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fbw, fbh);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    const bool heat = showHeatmap_ && referenceRelRmse_ >= 0 && heatmap_;
    view_.draw(heat ? heatmap_ : left_->frame().result(), 0, 0, viewW_, viewH_, heat ? 0.0f : exposure_);
    if (right_) view_.draw(right_->frame().result(), viewW_, 0, fbw - viewW_, viewH_, exposure_);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

} // namespace bounce::app
