// The Renderer's contract with techniques: parameters declared ParamUpdate::Uniform reach the running
// technique without rebuilding it, any other change makes it anew; the frame's version changes when (and
// only when) the camera, a light or the viewport changes, so that progressive techniques know when to
// start over.
#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/renderer.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

struct Probe {
    int made = 0;
    int uniformCalls = 0;
    double lastGain = -1.0;
};
Probe& probe()
{
    static Probe p;
    return p;
}

class ProbeTechnique : public gl::Technique {
public:
    explicit ProbeTechnique(const gl::ParamValues& v) { ++probe().made, probe().lastGain = v.get("gain"); }
    void render(gl::Frame&, gl::PassTimers&) override {}
    void setUniforms(const gl::ParamValues& v) override { ++probe().uniformCalls, probe().lastGain = v.get("gain"); }
};

gl::TechniqueInfo probeInfo()
{
    gl::TechniqueInfo info;
    info.name = "probe";
    info.params = {
        {"gain", gl::ParamType::Float, 1.0, 0.0, 10.0, "a uniform", false, gl::ParamUpdate::Uniform},
        {"size", gl::ParamType::Int, 4, 1, 64, "needs a rebuild"},
    };
    info.create = [](gl::Frame&, const gl::ParamValues& v) { return std::make_unique<ProbeTechnique>(v); };
    return info;
}

class RendererTest : public GlTest {};

TEST_F(RendererTest, UniformParametersDoNotRebuildTheTechnique)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const gl::TechniqueInfo info = probeInfo();
    probe() = {};
    gl::ParamValues values(info.params);
    gl::Renderer r(scene, info, gl::ParamValues(gl::frameParams()), values, 8, 8);
    EXPECT_EQ(probe().made, 1);

    values.set(info.params, "gain", "2.5");
    EXPECT_FALSE(r.setTechniqueValues(values));
    EXPECT_EQ(probe().made, 1);
    EXPECT_EQ(probe().uniformCalls, 1);
    EXPECT_EQ(probe().lastGain, 2.5);

    EXPECT_FALSE(r.setTechniqueValues(values)); // nothing changed: nothing to rebuild
    EXPECT_EQ(probe().made, 1);

    values.set(info.params, "size", "8");
    EXPECT_TRUE(r.setTechniqueValues(values));
    EXPECT_EQ(probe().made, 2);
    EXPECT_EQ(r.techniqueValues().getInt("size"), 8);
}

TEST_F(RendererTest, FrameVersionChangesOnlyWhenCameraLightsOrViewportChange)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::Renderer r(scene, "direct", gl::ParamValues(gl::frameParams()), gl::ParamValues(), 8, 8);
    gl::Frame& f = r.frame();
    const gl::FrameVersion v0 = f.version();

    f.setCamera(scene.camera); // the same camera: nothing moved
    r.renderFrame();
    EXPECT_EQ(f.version(), v0);

    core::Camera moved = scene.camera;
    moved.position.x += 0.01f;
    f.setCamera(moved);
    EXPECT_EQ(f.version().camera, v0.camera + 1);
    EXPECT_EQ(f.version().lights, v0.lights);

    std::vector<core::Light> lights = scene.lights;
    lights.at(0).position.y -= 0.01f;
    f.setLights(lights);
    EXPECT_EQ(f.version().lights, v0.lights + 1);

    const gl::FrameVersion v1 = f.version();
    f.resize(3, 5); // a viewport that is not a power of two
    EXPECT_EQ(f.version().camera, v1.camera + 1);
    f.resize(3, 5);
    EXPECT_EQ(f.version().camera, v1.camera + 1);
}

} // namespace
} // namespace bounce
