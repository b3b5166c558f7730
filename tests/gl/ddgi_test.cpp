// DDGI (gl/technique/ddgi/): the octahedral atlases (every inner texel's direction round-trips through the
// map, and every border texel holds the inner texel that lies across the tile's edge on the sphere, so
// that a bilinear lookup wraps), the furnace's closed form, Chebyshev visibility between two rooms split by
// a thin wall, and the hysteresis of the probes' irradiance after the light goes out. Tiny images and
// grids: llvmpipe on two cores.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/image.h"
#include "gl/frame/frame.h"
#include "gl/gl.h"
#include "gl/renderer.h"
#include "gl/resource/buffer.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"
#include "gl/technique/ddgi/bindings.h"
#include "gl/technique/ddgi/probe_field.h"
#include "gl/technique/technique.h"
#include "tests/gl/closed_box.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class DdgiTest : public GlTest {};

// The texels of a texture's level 0 as RGBA floats, row 0 first (GL's order).
std::vector<glm::vec4> texels(const gl::Texture& t)
{
    std::vector<glm::vec4> v(std::size_t(t.width()) * std::size_t(t.height()));
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(v.size() * sizeof(glm::vec4)), v.data());
    return v;
}

// A frame of `scene` (shadow maps only) and a probe field over it, updated `frames` times.
struct FieldRun {
    static gl::FrameSettings settings()
    {
        gl::FrameSettings fs;
        fs.width = 8;
        fs.height = 8;
        fs.shadowMapSize = 256;
        return fs;
    }
    FieldRun(core::Scene scene, const gl::ProbeFieldSettings& s)
        : scene(std::move(scene)), frame(this->scene, settings()), field(frame, s)
    {}
    void update(int frames)
    {
        for (int i = 0; i < frames; ++i) {
            gl::PassTimers timers;
            frame.beginFrame();
            frame.renderShadowMaps(timers);
            field.update(frame, timers);
        }
    }
    core::Scene scene; // the frame keeps a reference
    gl::Frame frame;
    gl::ProbeField field;
};

// The octahedral map's fold, in the map's own coordinates: its edges fold onto themselves ((1, v) and
// (1, -v) are one direction, as are (u, 1) and (-u, 1)), so a point carried past the edge x = 1 by h lands at
// (1 - h, -y), and past a corner it folds twice, onto the diagonally opposite corner.
glm::vec2 octFold(glm::vec2 e)
{
    if (e.x > 1.0f) e = {2.0f - e.x, -e.y};
    if (e.x < -1.0f) e = {-2.0f - e.x, -e.y};
    if (e.y > 1.0f) e = {-e.x, 2.0f - e.y};
    if (e.y < -1.0f) e = {-e.x, -2.0f - e.y};
    return e;
}

// A border texel must hold the inner texel its centre folds onto (octFold), so that a bilinear lookup
// across the tile's edge reads what a lookup across the map's wrapped edge reads. The inner texels must
// differ (a field of one value would hide a wrong copy): the test asks that under 1% of an active probe's
// inner texels equal another of its tile's (the distances clamped at the moments' maximum may repeat).
void expectBordersWrap(const std::vector<glm::vec4>& atlas, int atlasWidth, int tile,
                       const std::vector<glm::vec4>& states, int columns, const char* what)
{
    const int inner = tile - 2, probes = int(states.size());
    int checked = 0, wrong = 0, repeats = 0, active = 0;
    for (int p = 0; p < probes; ++p) {
        const glm::ivec2 corner = glm::ivec2(p % columns, p / columns) * tile;
        const auto at = [&](int x, int y) { return atlas[std::size_t(corner.y + y) * atlasWidth + corner.x + x]; };
        std::vector<glm::vec4> seen;
        if (states[std::size_t(p)].w != 0.0f) ++active;
        for (int y = 1; y <= inner && states[std::size_t(p)].w != 0.0f; ++y)
            for (int x = 1; x <= inner; ++x) {
                if (std::find(seen.begin(), seen.end(), at(x, y)) != seen.end()) ++repeats;
                seen.push_back(at(x, y));
            }
        for (int by = 0; by < tile; ++by)
            for (int bx = 0; bx < tile; ++bx) {
                if (bx > 0 && bx < tile - 1 && by > 0 && by < tile - 1) continue;
                const glm::vec2 e = (glm::vec2(bx - 1, by - 1) + 0.5f) * (2.0f / float(inner)) - 1.0f;
                const glm::ivec2 t = glm::clamp(glm::ivec2(glm::floor((octFold(e) + 1.0f) * (0.5f * float(inner)))),
                                                glm::ivec2(0), glm::ivec2(inner - 1));
                ++checked;
                if (at(t.x + 1, t.y + 1) != at(bx, by)) ++wrong;
            }
    }
    EXPECT_GE(active, probes / 2) << what << ": active probes";
    EXPECT_LE(repeats, active * inner * inner / 100)
        << what << ": inner texels of active probes equal to another of their tile's, of " << active * inner * inner;
    EXPECT_GT(checked, 0);
    EXPECT_EQ(wrong, 0) << what << ": border texels that do not hold the inner texel across the edge, of " << checked;
}

TEST_F(DdgiTest, EveryDirectionMapsToATexelAndBack)
{
    // 4096 directions and the six axes (the map's poles and the equator's corners), in the tile of probe 7
    // of an atlas 3 tiles wide: each lands inside its tile's inner texels, and the centre of the texel it
    // lands in decodes to a direction that lands back in that centre; so each direction lies within half a
    // texel (per axis of the map) of its texel's direction.
    const int count = 4096, n = count + 6, probe = 7, columns = 3;
    gl::Program program = gl::Program::compute("test.ddgi.octahedral", "test/ddgi_octahedral.comp");
    gl::Buffer out("test.ddgi.octahedral", std::size_t(n) * sizeof(glm::vec4));
    out.bindBase(GL_SHADER_STORAGE_BUFFER, 7);
    gl::Buffer states("test.ddgi.states", sizeof(glm::vec4)); // probes.glsl's block, which the map never reads
    states.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_DDGI_PROBES);
    for (const int inner : {6, 14}) {
        SCOPED_TRACE("inner " + std::to_string(inner));
        program.set("count", count);
        program.set("probe", probe);
        program.set("inner", inner);
        program.set("atlasColumns", columns);
        gl::dispatchCompute(program, {n, 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const std::vector<glm::vec4> r = out.download<glm::vec4>();
        const glm::vec2 lo = glm::vec2(glm::ivec2(probe % columns, probe / columns) * (inner + 2)) + 1.0f;
        int outside = 0, notBack = 0, far = 0;
        for (const glm::vec4& v : r) {
            const glm::vec2 at(v.x, v.y), back(v.z, v.w);
            if (glm::any(glm::lessThan(at, lo)) || glm::any(glm::greaterThan(at, lo + float(inner)))) ++outside;
            const glm::vec2 centre = glm::floor(glm::min(at, lo + float(inner) - 1e-3f)) + 0.5f;
            if (glm::any(glm::greaterThan(glm::abs(back - centre), glm::vec2(1e-3f)))) ++notBack;
            if (glm::any(glm::greaterThan(glm::abs(at - back), glm::vec2(0.5f + 1e-3f)))) ++far;
        }
        EXPECT_EQ(outside, 0) << "directions outside their tile's inner texels";
        EXPECT_EQ(notBack, 0) << "texel directions that do not map back to their texel's centre";
        EXPECT_EQ(far, 0) << "directions over half a texel from their texel's direction";
    }
}

TEST_F(DdgiTest, BordersHoldTheTexelAcrossTheEdge)
{
    gl::ProbeFieldSettings s;
    s.probes = 8;
    s.raysPerProbe = 512;
    s.hysteresis = 0.0f;
    FieldRun run(core::makeCornell("cornell-spot"), s);
    run.update(4); // the probes inside the blocks are moved out by the second and lit by the third
    const gl::ProbeField& f = run.field;
    const std::vector<glm::vec4> states = f.probeStates();
    expectBordersWrap(texels(f.irradiance()), f.irradiance().width(), gl::ProbeField::kIrradianceTile, states,
                      f.atlasColumns(), "irradiance");
    expectBordersWrap(texels(f.depth()), f.depth().width(), gl::ProbeField::kDepthTile, states, f.atlasColumns(),
                      "depth");
}

// The technique's indirect light after `frames` frames of a `width` x `height` render, with `sets` over its
// defaults.
gl::ParamValues ddgiValues(const std::vector<std::string>& sets)
{
    const gl::TechniqueInfo& info = gl::findTechnique("ddgi");
    gl::ParamValues values(info.params);
    for (const std::string& kv : sets) {
        const auto eq = kv.find('=');
        values.set(info.params, kv.substr(0, eq), kv.substr(eq + 1));
    }
    return values;
}

TEST_F(DdgiTest, FurnaceConvergesToTheClosedForm)
{
    // A closed box of albedo rho, every wall emitting L_e: the radiance everywhere is L_e / (1 - rho). The
    // frame's direct light holds L_e + rho L_e; the probes' rays bring back rho L_e + rho E / pi, whose
    // fixed point is E / pi = rho L_e / (1 - rho), and every pixel's indirect light rho^2 L_e / (1 - rho) =
    // 0.5. Still frames light the rays' hits, as they light the pixels, from one point of the emitting mesh
    // per frame (common/lighting.glsl's still form), so one frame's probes are noisy: the indirect light is
    // averaged here over 64 frames, after 24 at hysteresis 0.5 for the bounces to settle (each frame keeps
    // half of what the probes held; 24 frames leave under 1e-4 of the fixed point out).
    const float rho = 0.5f, le = 1.0f;
    const core::Scene scene = testing::closedBox("furnace", rho, le);
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 256);
    const int size = 16, frames = 64;
    gl::Renderer r(scene, "ddgi", frameValues, ddgiValues({"hysteresis=0.5", "probes=27", "raysPerProbe=128"}), size,
                   size);
    for (int i = 0; i < 24; ++i) r.renderFrame(false);
    std::vector<double> sum(std::size_t(size * size * 3), 0.0);
    for (int i = 0; i < frames; ++i) {
        r.renderFrame(false);
        const core::Image indirect = r.frame().read(r.frame().indirect());
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                for (int c = 0; c < 3; ++c) sum[std::size_t((y * size + x) * 3 + c)] += indirect.at(x, y)[c];
    }
    const double expected = rho * rho * le / (1.0 - rho);
    double mean = 0.0, worst = 0.0;
    for (double& v : sum) {
        v /= frames;
        mean += v / double(sum.size());
        worst = std::max(worst, std::abs(v / expected - 1.0));
    }
    std::printf("[ furnace  ] ddgi: mean indirect %.4f of the closed form, most relative error at a pixel %.4f\n",
                mean / expected, worst);
    EXPECT_NEAR(mean / expected, 1.0, 0.02) << "the image's mean indirect light over the closed form";
    // A pixel's mean keeps the one-point estimator's heavy tail (a hit next to the frame's point on the
    // emitter brings back a large radiance): 12% measured at the worst of 256 pixels.
    EXPECT_LT(worst, 0.2) << "the most relative error of a pixel's mean indirect light";
}

// Two rooms side by side, [0, 1] and [1, 2] along x, 1 m deep and high, open at the top, split by a wall 2 cm
// thick at x = 1 that reaches the top; a point light in the first room, the camera above looking down into
// both. Every surface Lambertian, albedo 0.5.
core::Scene twoRooms()
{
    core::Scene s;
    s.name = "two-rooms";
    core::Material m;
    m.name = "walls";
    m.baseColor = glm::vec3(0.5f);
    m.metallic = 0.0f;
    m.specular = 0.0f;
    s.materials.push_back(m);
    core::Mesh mesh;
    mesh.name = "rooms";
    const auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) { testing::addQuad(mesh, a, b, c, d); };
    quad({0, 0, 0}, {0, 0, 1}, {2, 0, 1}, {2, 0, 0});                 // floor, +y
    quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1});                 // x = 0, +x
    quad({2, 0, 0}, {2, 0, 1}, {2, 1, 1}, {2, 1, 0});                 // x = 2, -x
    quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0});                 // z = 0, +z
    quad({0, 0, 1}, {0, 1, 1}, {2, 1, 1}, {2, 0, 1});                 // z = 1, -z
    quad({0.99f, 0, 0}, {0.99f, 0, 1}, {0.99f, 1, 1}, {0.99f, 1, 0}); // the wall's face in the first room, -x
    quad({1.01f, 0, 0}, {1.01f, 1, 0}, {1.01f, 1, 1}, {1.01f, 0, 1}); // and in the second, +x
    quad({0.99f, 1, 0}, {0.99f, 1, 1}, {1.01f, 1, 1}, {1.01f, 1, 0}); // its top, +y
    s.meshes.push_back(mesh);
    core::Light light;
    light.name = "lamp";
    light.type = core::LightType::Point;
    light.position = {0.5f, 0.6f, 0.5f};
    light.intensity = glm::vec3(1.0f);
    s.lights.push_back(light);
    s.camera.position = {1.0f, 3.0f, 0.5f};
    s.camera.forward = {0.0f, -1.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, -1.0f};
    s.camera.yfovRad = 0.6f;
    s.camera.znear = 0.01f;
    s.camera.zfar = 10.0f;
    return s;
}

TEST_F(DdgiTest, ChebyshevVisibilityKeepsTheLitRoomBehindTheWall)
{
    // The probes (4 x 2 x 2, at x = 0.25, 0.75, 1.25, 1.75) put the wall between the second and third
    // columns: the dark room's floor between the wall and its own probes (x from 1.1 to 1.25) interpolates
    // the lit room's probes at x = 0.75 with its own. The distance moments put the lit room's probes behind
    // the wall: the light on that floor must stay under 1% of what the lit floor as far from the wall gets.
    // (The path tracer's answer there is no light: the wall reaches the top, and nothing above the rooms
    // sends it back.) Nearer the wall than 10 cm, the moments' spread at these grazing directions lets
    // Chebyshev's bound pass light through (16% of the lit side's at 4 cm: gl/technique/ddgi/README.md).
    const core::Scene scene = twoRooms();
    ASSERT_EQ(scene.validate(), "");
    const int w = 64, h = 32;
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 256);
    gl::Renderer r(scene, "ddgi", frameValues, ddgiValues({"probes=16", "raysPerProbe=256", "hysteresis=0"}), w, h);
    for (int i = 0; i < 8; ++i) r.renderFrame(false);
    const core::Image indirect = r.frame().read(r.frame().indirect());
    const core::Image position = r.frame().toImage(r.frame().readPositions());
    double lit = 0.0, dark = 0.0;
    int litCount = 0, darkCount = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec3 p(position.at(x, y)[0], position.at(x, y)[1], position.at(x, y)[2]);
            if (p.y > 0.01f) continue; // the floor only
            const float L = indirect.at(x, y)[1];
            if (p.x > 0.75f && p.x < 0.9f) {
                lit += L;
                ++litCount;
            } else if (p.x > 1.1f && p.x < 1.25f) {
                dark += L;
                ++darkCount;
            }
        }
    ASSERT_GT(litCount, 0);
    ASSERT_GT(darkCount, 0);
    lit /= litCount;
    dark /= darkCount;
    ASSERT_GT(lit, 0.0);
    EXPECT_LT(dark, 0.01 * lit) << "the dark floor near the wall gets " << dark << " against the lit floor's " << lit;
}

TEST_F(DdgiTest, IrradianceDecaysByTheHysteresisOnceTheLightIsOut)
{
    // One bounce (no probe lights the hits), the plain blend, every probe blended: with the light off, each
    // ray brings back black, so each texel keeps exactly the hysteresis' share of what it held, to the last
    // bits of a float.
    core::Scene scene = core::makeCornell("cornell-spot");
    gl::ProbeFieldSettings s;
    s.probes = 27;
    s.raysPerProbe = 128;
    s.hysteresis = 0.9f;
    s.bounces = false;
    s.fastTransitions = false;
    s.classification = false;
    FieldRun run(scene, s);
    run.update(3);
    std::vector<glm::vec4> before = texels(run.field.irradiance());
    std::vector<core::Light> dark = scene.lights;
    for (core::Light& l : dark) l.intensity = glm::vec3(0.0f);
    run.frame.setLights(dark);
    int lit = 0;
    for (const glm::vec4& v : before) lit += v.x > 0.0f ? 1 : 0;
    ASSERT_GT(lit, int(before.size()) / 2) << "texels with light before the light went out";
    for (int frame = 0; frame < 3; ++frame) {
        run.update(1);
        const std::vector<glm::vec4> after = texels(run.field.irradiance());
        double worst = 0.0;
        for (std::size_t i = 0; i < before.size(); ++i)
            for (int c = 0; c < 3; ++c)
                if (before[i][c] > 0.0f)
                    worst =
                        std::max(worst, std::abs(double(after[i][c]) / (double(s.hysteresis) * before[i][c]) - 1.0));
        EXPECT_LT(worst, 1e-6) << "frame " << frame << " after the light went out: most relative departure from h E";
        before = after;
    }
}

} // namespace
} // namespace bounce
