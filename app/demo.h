// The demo's state and its frame loop: the renderer on the left (or the whole window), the comparison
// technique on the right, the fly camera, the movable light, the reference image, the script. cmd_demo.cpp
// parses and checks the options (without a window) and hands them to a Demo.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/demo_script.h"
#include "app/demo_view.h"
#include "app/fly_camera.h"
#include "core/image.h"
#include "core/scene.h"
#include "gl/context/context.h"
#include "gl/renderer.h"

namespace bounce::app {

struct DemoSettings {
    core::Scene scene;
    std::string technique;                        // checked against the registry
    gl::ParamValues frameValues, techniqueValues; // checked against the declarations
    core::Image reference;                        // empty: none
    std::vector<DemoStep> script;                 // checked by parseDemoScript
    std::string frameLog;                         // CSV of every frame's times (empty: none), checked writable
    bool budgetDirectSamples = true;              // the budget sets moving.directSamples (the command line did not)
};

class Demo {
public:
    // Needs the window's context current; sets up Dear ImGui and the first renderer.
    Demo(gl::Context& context, DemoSettings settings);
    ~Demo();
    Demo(const Demo&) = delete;
    Demo& operator=(const Demo&) = delete;

    // Runs frames until the window closes or the script says quit; returns the exit status.
    int run();

private:
    bool runScript(); // the steps up to the next wait; false on quit
    void renderViews(int fbw, int fbh, float dt);
    void panel();
    void comparePanel();
    void halfLabels(int fbw);
    void present(int fbw, int fbh);

    void setTechnique(const std::string& name);
    void compareWith(const std::string& name); // "" stops comparing
    void applySet(const std::string& keyValue);
    // Frame parameters change the frame itself: both sides are rebuilt so that they stay comparable.
    void rebuildRenderers();
    // Writes the left half to FILE (.exr + .png) and, when comparing, the right half to FILE-right.
    void screenshot(const std::string& path);
    // A renderer at the view's size with the demo's frame parameters, lights and camera.
    std::unique_ptr<gl::Renderer> makeRenderer(const std::string& technique, const gl::ParamValues& values);

    gl::Context& context_;
    GLFWwindow* window_ = nullptr;
    DemoSettings s_;
    std::unique_ptr<gl::Renderer> left_, right_; // right_: the comparison, side by side (null: none)
    std::string rightName_ = "direct";
    gl::ParamValues rightValues_;
    DemoView view_;
    gl::Texture heatmap_;
    FlyCamera fly_;
    std::vector<core::Light> lights_;
    float exposure_ = 0.0f, speed_ = 0.5f;
    bool compareReference_ = false, showHeatmap_ = false;
    double referenceRelRmse_ = -1.0; // left against the reference (-1: not compared)
    double halvesRelRmse_ = -1.0;    // right against left (-1: not comparing)
    int viewW_ = 1, viewH_ = 1;
    int shot_ = 0, waitFrames_ = 0;
    int moveFrames_ = 0; // script: frames the camera still moves sideways

    // The frame budget (panel): while the camera or a light moves and a frame takes longer than the
    // budget, indirect light drops to a coarser resolution (gl::Renderer::setIndirectScale: 2, 4, 8) and
    // comes back to full resolution once the view has been still for kStillSeconds, where progressive
    // techniques accumulate again; a moving frame well under the budget takes more points of the direct
    // light instead (nextFrameBudget).
    static constexpr double kStillSeconds = 0.25;
    bool budgetOn_ = true;
    float budgetMs_ = 100.0f;
    FrameBudgetState budget_;
    void applyBudgetTo(gl::Renderer& r) const;
    double lastMoveTime_ = -1e30, frameMs_ = 0.0;
    std::string frameLog_; // the CSV rows so far, written at exit through a temporary name
    bool movingForLog_ = false;
    bool movedThisFrame_ = false;
    void applyBudget(double now);
};

} // namespace bounce::app
