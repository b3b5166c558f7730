// bounce demo: a window with Dear ImGui. Fly camera (right mouse drag to look, WASD/QE to move),
// technique selector with widgets generated from the technique's declared parameters, per-pass timing
// panel, a movable light (the scene is dynamic), screenshots (EXR + PNG), and a comparison view: two
// techniques side by side, or a technique against a reference EXR with a difference heat map and the
// relative RMSE. --script drives it without a person (the test runs it under Xvfb).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "app/commands.h"
#include "app/demo_view.h"
#include "app/options.h"
#include "app/render_job.h"
#include "core/image.h"
#include "core/metrics.h"
#include "gl/gl.h"

namespace bounce::app {

namespace {

const char* kUsage =
    "usage: bounce demo [--scene NAME|PATH] [--technique NAME] [--size WxH] [--set key=value]...\n"
    "                   [--reference FILE.exr] [--script STEPS]\n"
    "\n"
    "Opens a window. Right mouse drag looks around, W/A/S/D/Q/E move, F12 saves a screenshot\n"
    "(EXR + PNG in out/). The panel switches techniques, sets their parameters, moves the light and\n"
    "compares: two techniques side by side, or one against a reference EXR (heat map, relative RMSE).\n"
    "\n"
    "  --scene      built-in name or .gltf/.glb path   [cornell-spot]\n"
    "  --technique  initial technique                  [direct]\n"
    "  --size       window size                        [1024x768]\n"
    "  --reference  an EXR to compare against (same size as the render)\n"
    "  --script     comma-separated steps run in order, for automation:\n"
    "               wait:N (frames), technique:NAME, set:key=value, compare:NAME (side by side),\n"
    "               screenshot:FILE.exr (also writes the .png), quit\n";

struct Step {
    std::string verb, arg;
};

std::vector<Step> parseScript(const std::string& text)
{
    std::vector<Step> steps;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        if (item.empty()) continue;
        const auto colon = item.find(':');
        Step s{item.substr(0, colon), colon == std::string::npos ? "" : item.substr(colon + 1)};
        if (s.verb != "wait" && s.verb != "technique" && s.verb != "set" && s.verb != "compare" &&
            s.verb != "screenshot" && s.verb != "quit")
            throw UsageError("--script: unknown step '" + item + "'");
        steps.push_back(s);
    }
    return steps;
}

class FlyCamera {
public:
    explicit FlyCamera(const core::Camera& c) : camera_(c)
    {
        yaw_ = std::atan2(c.forward.x, c.forward.z);
        pitch_ = std::asin(glm::clamp(c.forward.y, -1.0f, 1.0f));
    }
    const core::Camera& camera() const { return camera_; }
    // Returns true when the camera moved.
    bool update(GLFWwindow* w, float dt, float speed)
    {
        bool moved = false;
        double mx, my;
        glfwGetCursorPos(w, &mx, &my);
        if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS && !ImGui::GetIO().WantCaptureMouse) {
            yaw_ -= float(mx - lastX_) * 0.003f;
            pitch_ = glm::clamp(pitch_ - float(my - lastY_) * 0.003f, -1.5f, 1.5f);
            moved |= mx != lastX_ || my != lastY_;
        }
        lastX_ = mx;
        lastY_ = my;
        camera_.forward = {std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), std::cos(pitch_) * std::cos(yaw_)};
        const glm::vec3 right = glm::normalize(glm::cross(camera_.forward, glm::vec3(0, 1, 0)));
        camera_.up = glm::normalize(glm::cross(right, camera_.forward));
        if (ImGui::GetIO().WantCaptureKeyboard) return moved;
        const struct { int key; glm::vec3 dir; } keys[] = {
            {GLFW_KEY_W, camera_.forward}, {GLFW_KEY_S, -camera_.forward}, {GLFW_KEY_D, right},
            {GLFW_KEY_A, -right},          {GLFW_KEY_E, glm::vec3(0, 1, 0)}, {GLFW_KEY_Q, glm::vec3(0, -1, 0)}};
        for (const auto& k : keys)
            if (glfwGetKey(w, k.key) == GLFW_PRESS) { camera_.position += k.dir * speed * dt; moved = true; }
        return moved;
    }

private:
    core::Camera camera_;
    float yaw_ = 0, pitch_ = 0;
    double lastX_ = 0, lastY_ = 0;
};

// Parameter widgets generated from the declaration; returns true when a value changed.
bool paramWidgets(const std::vector<gl::ParamDecl>& decls, gl::ParamValues& values)
{
    bool changed = false;
    for (const gl::ParamDecl& d : decls) {
        double v = values.get(d.name);
        if (d.type == gl::ParamType::Bool) {
            bool b = v != 0.0;
            if (ImGui::Checkbox(d.name.c_str(), &b)) { values.setValue(d.name, b ? 1.0 : 0.0); changed = true; }
        } else if (d.type == gl::ParamType::Int) {
            int i = int(v);
            if (ImGui::DragInt(d.name.c_str(), &i, 1.0f, int(d.min), int(d.max), "%d", ImGuiSliderFlags_AlwaysClamp)) {
                values.setValue(d.name, i);
                changed = true;
            }
        } else {
            float f = float(v);
            const float speed = float((d.max - d.min) / 500.0);
            if (ImGui::DragFloat(d.name.c_str(), &f, speed, float(d.min), float(d.max), "%.4g",
                                 ImGuiSliderFlags_AlwaysClamp)) {
                values.setValue(d.name, f);
                changed = true;
            }
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", d.meaning.c_str());
    }
    return changed;
}

void saveScreenshot(const core::Image& image, std::filesystem::path path)
{
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    path.replace_extension(".exr");
    core::writeExr(path.string(), image);
    path.replace_extension(".png");
    core::writePng(path.string(), image);
    std::printf("screenshot: %s (+ .exr)\n", path.string().c_str());
}

} // namespace

int cmdDemo(const Args& args)
{
    const Options o(args, {{"scene"}, {"technique"}, {"size"}, {"set", true, true}, {"reference"}, {"script"}}, kUsage);
    if (o.helpRequested()) { std::fputs(kUsage, stdout); return 0; }
    if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'\n\n" + kUsage);
    int width = 1024, height = 768;
    if (o.has("size")) parseSize(o.get("size"), width, height);
    std::vector<Step> script = parseScript(o.get("script"));
    const std::string sceneArg = o.get("scene", "cornell-spot");
    std::string techniqueName = o.get("technique", "direct");
    const gl::TechniqueInfo* info = nullptr;
    try { info = &gl::findTechnique(techniqueName); } catch (const std::invalid_argument& e) { throw UsageError(e.what()); }
    gl::ParamValues frameValues(gl::frameParams()), techniqueValues(info->params);
    applySets(o.all("set"), *info, frameValues, techniqueValues);
    core::Image reference;
    if (o.has("reference")) {
        try { reference = core::readImage(o.get("reference")); } catch (const core::ImageError& e) { throw UsageError(e.what()); }
    }
    const core::Scene scene = loadSceneForCli(sceneArg);

    gl::ContextOptions co;
    co.width = width;
    co.height = height;
    co.title = "Bounce - " + sceneArg;
    std::unique_ptr<gl::Context> context;
    try { context = gl::Context::create(gl::Backend::Glfw, co); } catch (const gl::ContextError& e) { throw UsageError(e.what()); }
    GLFWwindow* window = context->window();
    std::printf("GL renderer: %s (%s)\n", context->info().renderer.c_str(), context->info().platform.c_str());

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");

    // The render resolution follows the window (half of it in side-by-side mode).
    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(window, &fbw, &fbh);
    auto renderer = std::make_unique<gl::Renderer>(scene, techniqueName, frameValues, techniqueValues,
                                                   std::max(fbw, 1), std::max(fbh, 1));
    std::unique_ptr<gl::Renderer> second; // the comparison technique, side by side
    std::string secondName = "direct";
    gl::ParamValues secondValues(gl::findTechnique(secondName).params);
    DemoView view;
    gl::Texture heatmapTexture, secondTexture;
    FlyCamera fly(scene.camera);
    std::vector<core::Light> lights = scene.lights;
    float exposure = 0.0f, speed = 0.5f;
    bool compareReference = !reference.rgb.empty(), showHeatmap = false;
    double relRmse = -1.0;
    int shot = 0, waitFrames = 0;
    double last = glfwGetTime();

    while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        const double now = glfwGetTime();
        const float dt = float(now - last);
        last = now;

        // Automation: run script steps until a wait.
        bool quit = false;
        while (waitFrames == 0 && !script.empty()) {
            const Step s = script.front();
            script.erase(script.begin());
            if (s.verb == "wait") waitFrames = std::max(1, std::atoi(s.arg.c_str()));
            else if (s.verb == "technique") {
                const gl::TechniqueInfo& t = gl::findTechnique(s.arg);
                techniqueName = t.name;
                techniqueValues = gl::ParamValues(t.params);
                renderer->setTechnique(techniqueName, techniqueValues);
            } else if (s.verb == "set") {
                applySets({s.arg}, renderer->technique(), frameValues, techniqueValues);
                renderer->setTechnique(techniqueName, techniqueValues);
            } else if (s.verb == "compare") {
                secondName = s.arg;
                secondValues = gl::ParamValues(gl::findTechnique(secondName).params);
                second.reset();
                second = std::make_unique<gl::Renderer>(scene, secondName, frameValues, secondValues, 1, 1);
            } else if (s.verb == "screenshot") saveScreenshot(renderer->image(), s.arg);
            else if (s.verb == "quit") quit = true;
        }
        if (quit) break;
        if (waitFrames > 0) --waitFrames;

        glfwGetFramebufferSize(window, &fbw, &fbh);
        if (fbw <= 0 || fbh <= 0) continue;
        const int viewW = second ? std::max(1, fbw / 2) : fbw;
        renderer->frame().resize(viewW, fbh);
        fly.update(window, dt, speed);
        renderer->frame().setCamera(fly.camera());
        renderer->renderFrame();
        if (second) {
            second->frame().resize(viewW, fbh);
            second->frame().setCamera(fly.camera());
            second->renderFrame();
        }
        if (compareReference && reference.width == viewW && reference.height == fbh) {
            const core::Image img = renderer->image();
            relRmse = core::relativeRmse(img, reference);
            if (showHeatmap) DemoView::upload(core::errorHeatmap(img, reference), heatmapTexture);
        } else {
            relRmse = -1.0;
        }

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ImGui::Begin("Bounce");
        ImGui::Text("%s", context->info().renderer.c_str());
        if (ImGui::BeginCombo("technique", techniqueName.c_str())) {
            for (const gl::TechniqueInfo& t : gl::techniques())
                if (ImGui::Selectable(t.name.c_str(), t.name == techniqueName)) {
                    techniqueName = t.name;
                    techniqueValues = gl::ParamValues(t.params);
                    renderer->setTechnique(techniqueName, techniqueValues);
                }
            ImGui::EndCombo();
        }
        ImGui::TextWrapped("%s", renderer->technique().summary.c_str());
        if (paramWidgets(renderer->technique().params, techniqueValues)) renderer->setTechnique(techniqueName, techniqueValues);
        if (ImGui::CollapsingHeader("frame")) {
            if (paramWidgets(gl::frameParams(), frameValues)) {
                renderer = std::make_unique<gl::Renderer>(scene, techniqueName, frameValues, techniqueValues, viewW, fbh);
                renderer->frame().setLights(lights);
            }
        }
        if (!lights.empty() && ImGui::CollapsingHeader("light", ImGuiTreeNodeFlags_DefaultOpen)) {
            core::Light& l = lights[0];
            bool moved = ImGui::DragFloat3("position", &l.position.x, 0.005f);
            float yaw = std::atan2(l.direction.x, l.direction.z), pitch = std::asin(glm::clamp(l.direction.y, -1.f, 1.f));
            if (ImGui::DragFloat("yaw", &yaw, 0.01f) | ImGui::DragFloat("pitch", &pitch, 0.01f, -1.57f, 1.57f)) {
                l.direction = {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
                moved = true;
            }
            if (moved) {
                renderer->frame().setLights(lights);
                if (second) second->frame().setLights(lights);
            }
        }
        ImGui::DragFloat("exposure", &exposure, 0.05f, -10.f, 10.f);
        ImGui::DragFloat("move speed (m/s)", &speed, 0.01f, 0.01f, 100.f);
        if (ImGui::CollapsingHeader("passes (GPU ms)", ImGuiTreeNodeFlags_DefaultOpen)) {
            double total = 0;
            for (const gl::PassStat& p : renderer->timers().lastFrame()) {
                ImGui::Text("%-16s %8.3f", p.pass.c_str(), p.medianMs);
                total += p.medianMs;
            }
            ImGui::Text("%-16s %8.3f", "total", total);
            for (const gl::Counter& c : renderer->counters()) ImGui::Text("%-16s %g", c.name.c_str(), c.value);
        }
        if (ImGui::CollapsingHeader("compare")) {
            bool sideBySide = bool(second);
            if (ImGui::Checkbox("side by side with", &sideBySide)) {
                if (sideBySide) second = std::make_unique<gl::Renderer>(scene, secondName, frameValues, secondValues, 1, 1);
                else second.reset();
            }
            if (second && ImGui::BeginCombo("second technique", secondName.c_str())) {
                for (const gl::TechniqueInfo& t : gl::techniques())
                    if (ImGui::Selectable(t.name.c_str(), t.name == secondName)) {
                        secondName = t.name;
                        secondValues = gl::ParamValues(t.params);
                        second->setTechnique(secondName, secondValues);
                    }
                ImGui::EndCombo();
            }
            if (!reference.rgb.empty()) {
                ImGui::Checkbox("against the reference", &compareReference);
                ImGui::Checkbox("heat map", &showHeatmap);
                if (relRmse >= 0) ImGui::Text("relative RMSE %.4f", relRmse);
                else if (compareReference) ImGui::Text("reference is %dx%d; view is %dx%d", reference.width, reference.height, viewW, fbh);
            }
        }
        if (ImGui::Button("screenshot (F12)") || ImGui::IsKeyPressed(GLFW_KEY_F12, false))
            saveScreenshot(renderer->image(), "out/screenshot-" + std::to_string(shot++) + ".exr");
        ImGui::End();
        ImGui::Render();

        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, fbw, fbh);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        const bool heat = showHeatmap && relRmse >= 0 && heatmapTexture;
        view.draw(heat ? heatmapTexture : renderer->frame().result(), 0, 0, viewW, fbh, heat ? 0.0f : exposure);
        if (second) view.draw(second->frame().result(), viewW, 0, fbw - viewW, fbh, exposure);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        context->swapBuffers();
    }

    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return 0;
}

} // namespace bounce::app
