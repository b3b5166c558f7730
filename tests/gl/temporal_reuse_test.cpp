// Temporal reuse (gl/frame/temporal_reuse.h, issue 58's "Reprojection" tests): closed cases on a plane seen
// head-on, where a camera moved parallel to it by whole pixels shifts the image by exactly those pixels, so
// that what each pixel's history must be is known: the signal of the pixel k to the side in the previous
// frame, or none where that point was off screen, hidden or on another surface.
//
// Exact comparisons (tolerance 0) are stated as such: the pass snaps a reprojected position within 1/64
// pixel of a texel centre to that texel (the position rebuilt from depth is off by float rounding only), so
// a still camera or a whole-pixel move copies texels, and the blend h + (c - h) w of the frame after a
// restart (w = 1/2) halves a history exactly when the current value is 0.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/scene.h"
#include "gl/frame/frame.h"
#include "gl/frame/temporal_reuse.h"
#include "gl/gl.h"
#include "tests/gl/closed_box.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class TemporalReuseTest : public GlTest {};

constexpr float kHalfHeightTan = 0.5f; // tan of half the vertical field of view
constexpr float kPlaneDistance = 2.0f; // m, camera to the plane z = 0
constexpr float kPlaneRight = 1.0f;    // the plane's right edge (x, m): background beyond it

// One pixel's width on the plane for a viewport `height` pixels high (square pixels).
float pixelOnPlane(int height)
{
    return 2.0f * kPlaneDistance * kHalfHeightTan / float(height);
}

// A plane z = 0 facing +z from x = -5 to kPlaneRight, y = -5..5, its shading normal `normal` (the face's, +z,
// unless a test tilts it); with `occluder`, a small quad facing the camera at z = 1 in front of it.
core::Scene planeScene(bool occluder, glm::vec3 normal = {0.0f, 0.0f, 1.0f}, float occluderShift = 0.0f)
{
    core::Scene s;
    s.name = "temporal-plane";
    core::Material m;
    m.name = "grey";
    m.baseColor = glm::vec3(0.5f);
    m.metallic = 0.0f;
    m.specular = 0.0f;
    s.materials.push_back(m);
    core::Mesh plane;
    plane.name = "plane";
    testing::addQuad(plane, {-5, -5, 0}, {kPlaneRight, -5, 0}, {kPlaneRight, 5, 0}, {-5, 5, 0});
    for (glm::vec3& n : plane.normals) n = glm::normalize(normal);
    s.meshes.push_back(plane);
    if (occluder) {
        core::Mesh box;
        box.name = "occluder";
        // 0.25 m x 0.5 m at 1 m from the camera: columns 8..15 and rows 8..23 of a 64x32 view, its edges on
        // pixel boundaries, so that no pixel centre sits on one.
        const float d = occluderShift;
        testing::addQuad(box, {-0.75f + d, -0.25f, 1}, {-0.5f + d, -0.25f, 1}, {-0.5f + d, 0.25f, 1},
                         {-0.75f + d, 0.25f, 1});
        s.meshes.push_back(box);
    }
    s.camera = core::Camera{};
    return s;
}

// Looking down -z at the plane from kPlaneDistance, moved by `x` metres along it.
core::Camera planeCamera(float x)
{
    core::Camera c;
    c.position = {x, 0.0f, kPlaneDistance};
    c.forward = {0.0f, 0.0f, -1.0f};
    c.up = {0.0f, 1.0f, 0.0f};
    c.yfovRad = 2.0f * std::atan(kHalfHeightTan);
    c.znear = 0.1f;
    c.zfar = 10.0f;
    return c;
}

gl::FrameSettings smallFrame(int width, int height)
{
    gl::FrameSettings s;
    s.width = width;
    s.height = height;
    s.shadowMapSize = 64;
    return s;
}

// The frame's G-buffer from `camera` (a moving frame: pixel centres, no jitter).
void renderGeometry(gl::Frame& frame, const core::Camera& camera, gl::PassTimers& timers)
{
    frame.setCamera(camera);
    frame.beginFrame();
    frame.renderGBuffer(timers);
    timers.endFrame();
}

gl::Texture makeSignal(int width, int height)
{
    return gl::Texture::create2D("test.signal", GL_RGBA32F, width, height);
}

// Four floats per pixel, GL rows (row 0 at the bottom), as readFloats and readPositions give them.
void upload(gl::Texture& t, const std::vector<float>& rgba)
{
    glTextureSubImage2D(t.id(), 0, 0, 0, t.width(), t.height(), GL_RGBA, GL_FLOAT, rgba.data());
}

std::size_t at(int x, int y, int width)
{
    return (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
}

// A smooth function of the world position, different at every pixel of the plane: what a signal computed
// from the surface (light) looks like to the pass. Background: `background`.
std::vector<float> worldSignal(const std::vector<float>& positions, float background)
{
    std::vector<float> s(positions.size());
    for (std::size_t i = 0; i < positions.size(); i += 4) {
        const bool geometry = positions[i + 3] != 0.0f;
        const float x = positions[i], y = positions[i + 1], z = positions[i + 2];
        s[i + 0] = geometry ? 10.0f + x : background;
        s[i + 1] = geometry ? 10.0f + y + 0.25f * x : background;
        s[i + 2] = geometry ? 10.0f + z - 0.5f * y : background;
        s[i + 3] = 1.0f;
    }
    return s;
}

// Per pixel: the geometry's value, or `background` where the frame has none.
std::vector<float> constantSignal(const std::vector<float>& positions, float value, float background)
{
    std::vector<float> s(positions.size());
    for (std::size_t i = 0; i < positions.size(); i += 4) {
        const float v = positions[i + 3] != 0.0f ? value : background;
        s[i] = s[i + 1] = s[i + 2] = v;
        s[i + 3] = 1.0f;
    }
    return s;
}

gl::TemporalReuseSettings noClamp()
{
    gl::TemporalReuseSettings s;
    s.clamp = false;
    return s;
}

// Two frames of the plane camera through one pass without the clamp: `before`'s G-buffer with the signal 5
// on its geometry, then `after`'s with 1. The positions each frame saw (GL rows) and the output.
struct TwoFrames {
    std::vector<float> was, positions, out;
};

TwoFrames fiveThenOne(const core::Scene& before, const core::Scene& after)
{
    gl::Frame first(before, smallFrame(64, 32)), second(after, smallFrame(64, 32));
    gl::PassTimers timers;
    gl::TemporalReuse reuse(noClamp());
    gl::Texture t = makeSignal(64, 32);
    TwoFrames r;
    renderGeometry(first, planeCamera(0.0f), timers);
    r.was = first.readPositions();
    upload(t, constantSignal(r.was, 5.0f, 0.0f));
    reuse.apply(first, {&t}, timers);
    renderGeometry(second, planeCamera(0.0f), timers);
    r.positions = second.readPositions();
    upload(t, constantSignal(r.positions, 1.0f, 0.0f));
    reuse.apply(second, {&t}, timers);
    r.out = t.readFloats(0, 4);
    return r;
}

// 1. A still camera and a signal that does not change: every frame's output is the signal itself, exactly
// (the history is the pixel's own texel, in its own neighbourhood, and h + (c - h) w is h when c = h), on a
// scene with walls at many depths and normals and at a size that is no power of two.
TEST_F(TemporalReuseTest, StillCameraConstantSignalComesBackExactly)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::Frame frame(scene, smallFrame(37, 23));
    gl::PassTimers timers;
    gl::TemporalReuse reuse;
    renderGeometry(frame, scene.camera, timers);
    // A pattern with edges at every pixel, so that a tap of a neighbour anywhere shows.
    std::vector<float> signal(std::size_t(37 * 23 * 4));
    for (std::size_t i = 0; i < signal.size(); ++i) signal[i] = float((i * 7919) % 101) * 0.125f;
    gl::Texture t = makeSignal(37, 23);
    for (int f = 0; f < 5; ++f) {
        renderGeometry(frame, scene.camera, timers);
        upload(t, signal);
        reuse.apply(frame, {&t}, timers);
        EXPECT_TRUE(reuse.hasHistory());
        const std::vector<float> out = t.readFloats(0, 4);
        int differ = 0;
        for (std::size_t i = 0; i < out.size(); ++i) differ += out[i] != signal[i];
        EXPECT_EQ(differ, 0) << "frame " << f << ": values that are not the signal's own";
    }
}

struct Shift {
    int width, height, pixels; // viewport and the camera's move, in pixels on the plane
};

// 2, 3 and 5. The camera moves left by k pixels over the plane: frame 2's pixel (x, y) sees the point
// frame 1's pixel (x - k, y) saw. Frame 1's signal is a function of the world position, frame 2's is 0 on
// the plane (7 on the background, right of the plane's edge), the clamp off: each pixel's output is half
// its history (n = 2), so twice the output must be frame 1's signal k pixels to the left, exactly. The k
// columns on the left that enter the view take no history: their output is the current value (0), as is
// every background pixel's (7). At 64x32 and at 37x23 (no power of two, pixels of 2/23 m that no float
// holds exactly, and the plane's edge on a pixel boundary in both).
// The plane without an occluder at w x h, and a first frame from planeCamera(0) whose signal (`first`, the
// world signal, background 7) the reuse took as its history, unclamped.
struct PlaneHistory {
    core::Scene scene = planeScene(false);
    gl::Frame frame;
    gl::PassTimers timers;
    gl::TemporalReuse reuse{noClamp()};
    gl::Texture t;
    std::vector<float> first;
    PlaneHistory(int w, int h) : frame(scene, smallFrame(w, h)), t(makeSignal(w, h))
    {
        renderGeometry(frame, planeCamera(0.0f), timers);
        first = worldSignal(frame.readPositions(), 7.0f);
        upload(t, first);
        reuse.apply(frame, {&t}, timers);
    }
};

void expectWholePixelMoveReprojectsExactly(const Shift& shift)
{
    const int w = shift.width, h = shift.height, k = shift.pixels;
    PlaneHistory p(w, h);
    gl::Frame& frame = p.frame;
    gl::PassTimers& timers = p.timers;
    gl::TemporalReuse& reuse = p.reuse;
    gl::Texture& t = p.t;
    const std::vector<float>& first = p.first;

    renderGeometry(frame, planeCamera(-float(k) * pixelOnPlane(h)), timers);
    const std::vector<float> positions = frame.readPositions();
    const std::vector<float> current = constantSignal(positions, 0.0f, 7.0f);
    upload(t, current);
    reuse.apply(frame, {&t}, timers);
    const std::vector<float> out = t.readFloats(0, 4);

    int reprojected = 0, entered = 0, background = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = at(x, y, w);
            if (positions[i + 3] == 0.0f) {
                ++background;
                for (int c = 0; c < 3; ++c) EXPECT_EQ(out[i + c], 7.0f) << "background " << x << "," << y;
            } else if (x < k) {
                ++entered;
                for (int c = 0; c < 3; ++c) EXPECT_EQ(out[i + c], 0.0f) << "entered at the border " << x << "," << y;
            } else {
                ++reprojected;
                const std::size_t from = at(x - k, y, w);
                for (int c = 0; c < 3; ++c)
                    EXPECT_EQ(2.0f * out[i + c], first[from + c])
                        << "pixel " << x << "," << y << " channel " << c << ": history from " << x - k << "," << y;
            }
        }
    EXPECT_GT(reprojected, w * h / 2);
    EXPECT_EQ(entered, k * h);
    EXPECT_GT(background, 0);
}

TEST_F(TemporalReuseTest, WholePixelMoveReprojectsExactly)
{
    for (const Shift& shift : {Shift{64, 32, 3}, Shift{37, 23, 2}, Shift{37, 23, 1}}) {
        SCOPED_TRACE(std::to_string(shift.width) + "x" + std::to_string(shift.height) + " by " +
                     std::to_string(shift.pixels));
        expectWholePixelMoveReprojectsExactly(shift);
    }
}

// A move by a fraction of a pixel (0.37 of one, the common case on a moving camera) resamples the history
// between texel centres: for a signal linear in the world position the bilinear taps reproduce it
// exactly, so twice the output (n = 2, the current value 0) must be frame 2's own world signal at every
// pixel that keeps a history, to float rounding. A reprojection that lags or leads the camera by a
// fraction of a pixel reads off here by that fraction of the signal's slope per pixel.
TEST_F(TemporalReuseTest, SubPixelMoveReprojectsALinearSignal)
{
    constexpr int w = 37, h = 23;
    PlaneHistory p(w, h);
    renderGeometry(p.frame, planeCamera(-0.37f * pixelOnPlane(h)), p.timers);
    const std::vector<float> positions = p.frame.readPositions();
    const std::vector<float> want = worldSignal(positions, 7.0f);
    upload(p.t, constantSignal(positions, 0.0f, 7.0f));
    p.reuse.apply(p.frame, {&p.t}, p.timers);
    const std::vector<float> out = p.t.readFloats(0, 4);
    int compared = 0;
    float worst = 0.0f;
    for (int y = 0; y < h; ++y)
        for (int x = 1; x < w; ++x) { // column 0 entered the view
            const std::size_t i = at(x, y, w);
            if (positions[i + 3] == 0.0f || x + 1 >= w || positions[at(x + 1, y, w) + 3] == 0.0f) continue;
            ++compared;
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(2.0f * out[i + c] - want[i + c]));
        }
    const float slope = pixelOnPlane(h); // the signal's change per pixel along x
    std::printf("[ measured ] %d pixels, largest difference %.3g (%.3g of a pixel's slope)\n", compared, worst,
                worst / slope);
    EXPECT_GT(compared, w * h / 2);
    EXPECT_LT(worst, 0.01f * slope);
}

// A signal quadratic in the world's x along the plane (so in the screen's x: the plane faces the camera),
// rising over the whole view: 10 + (x + 5)^2 in every channel, background 7.
std::vector<float> quadraticSignal(const std::vector<float>& positions)
{
    std::vector<float> s(positions.size());
    for (std::size_t i = 0; i < positions.size(); i += 4) {
        const float u = positions[i] + 5.0f;
        const float v = positions[i + 3] != 0.0f ? 10.0f + u * u : 7.0f;
        s[i] = s[i + 1] = s[i + 2] = v;
        s[i + 3] = 1.0f;
    }
    return s;
}

// The same fraction of a pixel (0.37) with a signal of curvature: the bilinear blend reads a quadratic
// between texel centres off by its second difference times f (1 - f) / 2, a blur it adds at every frame of
// a moving camera; Catmull-Rom's cubic (Keys' a = -1/2) reproduces quadratics, so with temporal.filter's
// catmull-rom twice the output must be frame 2's own signal to float rounding wherever the 4x4 texels around
// the point all lie on the plane. The bilinear blend must read off here, or this test could not tell the
// two apart.
TEST_F(TemporalReuseTest, SubPixelMoveWithCatmullRomReprojectsAQuadraticSignal)
{
    constexpr int w = 37, h = 23;
    const float pixel = pixelOnPlane(h);
    const float secondDifference = 2.0f * pixel * pixel; // of the signal from one pixel to the next
    for (const bool catmullRom : {true, false}) {
        PlaneHistory p(w, h);
        upload(p.t, quadraticSignal(p.frame.readPositions()));
        p.reuse.reset();
        p.reuse.apply(p.frame, {&p.t}, p.timers);
        p.reuse.settings.catmullRom = catmullRom;
        renderGeometry(p.frame, planeCamera(-0.37f * pixel), p.timers);
        const std::vector<float> positions = p.frame.readPositions();
        const std::vector<float> want = quadraticSignal(positions);
        upload(p.t, constantSignal(positions, 0.0f, 7.0f));
        p.reuse.apply(p.frame, {&p.t}, p.timers);
        const std::vector<float> out = p.t.readFloats(0, 4);
        int compared = 0;
        float worst = 0.0f;
        for (int y = 2; y + 2 < h; ++y)
            for (int x = 2; x + 2 < w; ++x) { // the point lies left of the centre: texels x - 2 .. x + 1
                bool plane = true;
                for (int dy = -2; dy <= 2; ++dy)
                    for (int dx = -2; dx <= 2; ++dx) plane = plane && positions[at(x + dx, y + dy, w) + 3] != 0.0f;
                if (!plane) continue;
                ++compared;
                const std::size_t i = at(x, y, w);
                for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(2.0f * out[i + c] - want[i + c]));
            }
        std::printf("[ measured ] %s: %d pixels, largest difference %.3g (%.3g of the second difference)\n",
                    catmullRom ? "catmull-rom" : "bilinear", compared, worst, worst / secondDifference);
        EXPECT_GT(compared, w * h / 3);
        if (catmullRom)
            EXPECT_LT(worst, 0.01f * secondDifference);
        else
            EXPECT_GT(worst, 0.05f * secondDifference) << "the bilinear blend's blur (0.117 of it at f = 0.37)";
    }
}

// 3. An occluder in front of the plane goes away (frame 2 renders the scene without it, same camera): the
// pixels it covered now see the plane, which the previous G-buffer has at another depth (1 m against 2 m),
// and take no history (output: the current value, 1); every other plane pixel blends its history (5) with
// it: 5 + (1 - 5) / 2 = 3.
TEST_F(TemporalReuseTest, DisoccludedPixelsTakeNoHistory)
{
    const TwoFrames f = fiveThenOne(planeScene(true), planeScene(false));
    const std::vector<float>&was = f.was, &positions = f.positions, &out = f.out;
    int disoccluded = 0, kept = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            const std::size_t i = at(x, y, 64);
            if (positions[i + 3] == 0.0f) continue;
            const bool hidden = was[i + 2] > 0.5f; // frame 1 saw the occluder (z = 1) here
            (hidden ? disoccluded : kept) += 1;
            EXPECT_EQ(out[i], hidden ? 1.0f : 3.0f) << x << "," << y << (hidden ? " (disoccluded)" : "");
        }
    EXPECT_EQ(disoccluded, 8 * 16) << "the occluder's pixels";
    EXPECT_GT(kept, 1000);
}

// 3. An edge moves by one pixel (the occluder 1/32 m, one pixel at 1 m, to the right; the same camera): the
// column it now covers sees the occluder where the previous frame saw the plane, the column it left sees the
// plane where the previous frame saw the occluder. Each of them has both surfaces in its 3x3 neighbourhood,
// as a silhouette pixel has when its jittered samples land on either side, and keeps its history:
// 5 + (1 - 5) / 2 = 3 at every pixel. (Tested against the pixel's own surface alone, those two columns took
// none: 1.)
TEST_F(TemporalReuseTest, SurfaceOfANeighbourKeepsTheHistory)
{
    const TwoFrames f = fiveThenOne(planeScene(true), planeScene(true, {0.0f, 0.0f, 1.0f}, 1.0f / 32.0f));
    const std::vector<float>&was = f.was, &positions = f.positions, &out = f.out;
    int changed = 0, wrong = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            const std::size_t i = at(x, y, 64);
            if (positions[i + 3] == 0.0f) continue;
            changed += (was[i + 2] > 0.5f) != (positions[i + 2] > 0.5f);
            wrong += out[i] != 3.0f;
            EXPECT_EQ(out[i], 3.0f) << x << "," << y;
        }
    EXPECT_EQ(changed, 2 * 16) << "one column covered, one uncovered, 16 rows each";
    EXPECT_EQ(wrong, 0);
}

// 3. The camera moves by one pixel of the plane (1/16 m at 2 m); the occluder, at half the distance, moves
// by two: one column of the plane beside it is uncovered by parallax. Those pixels saw the occluder in the
// previous frame where they reproject, and the occluder is in their 3x3 neighbourhood now, but it moves
// otherwise than they do: they take no history (1), where without the motion test they took the occluder's
// (9, then (9 + 1) / 2 = 5) and every later frame would have drawn the trail on. The rest of the plane keeps
// its own history, 5 + (1 - 5) / 2 = 3, the occluder its own, 5.
TEST_F(TemporalReuseTest, SurfaceUncoveredByParallaxTakesNoHistoryOfTheEdge)
{
    constexpr int w = 64, h = 32;
    const core::Scene scene = planeScene(true);
    gl::Frame frame(scene, smallFrame(w, h));
    gl::PassTimers timers;
    gl::TemporalReuse reuse(noClamp());
    gl::Texture t = makeSignal(w, h);
    renderGeometry(frame, planeCamera(0.0f), timers);
    const std::vector<float> was = frame.readPositions();
    std::vector<float> first = constantSignal(was, 5.0f, 0.0f);
    for (std::size_t i = 0; i < was.size(); i += 4)
        if (was[i + 3] != 0.0f && was[i + 2] > 0.5f) first[i] = first[i + 1] = first[i + 2] = 9.0f;
    upload(t, first);
    reuse.apply(frame, {&t}, timers);
    renderGeometry(frame, planeCamera(pixelOnPlane(h)), timers);
    const std::vector<float> positions = frame.readPositions();
    upload(t, constantSignal(positions, 1.0f, 0.0f));
    reuse.apply(frame, {&t}, timers);
    const std::vector<float> out = t.readFloats(0, 4);
    int uncovered = 0, plane = 0, occluder = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x + 1 < w; ++x) { // the last column entered the view
            const std::size_t i = at(x, y, w);
            if (positions[i + 3] == 0.0f) continue;
            if (positions[i + 2] > 0.5f) {
                ++occluder;
                EXPECT_EQ(out[i], 5.0f) << "occluder " << x << "," << y;
                continue;
            }
            ++plane;
            uncovered += out[i] == 1.0f;
            EXPECT_TRUE(out[i] == 1.0f || out[i] == 3.0f) << "plane " << x << "," << y << ": " << out[i];
        }
    EXPECT_EQ(occluder, 8 * 16);
    EXPECT_EQ(uncovered, 16) << "one column of 16 rows uncovered";
    EXPECT_GT(plane, 1000);
}

// 3. The same point under a shading normal turned by more than the tolerance is another surface: no
// history; turned by less, the history is kept. normalTolerance 0.1 (1 - cos): 0.2 rejects, 0.05 keeps.
TEST_F(TemporalReuseTest, NormalChangeBeyondToleranceTakesNoHistory)
{
    const core::Scene flat = planeScene(false);
    for (float cosine : {0.8f, 0.95f}) {
        SCOPED_TRACE(cosine);
        const TwoFrames f = fiveThenOne(flat, planeScene(false, {0.0f, std::sqrt(1.0f - cosine * cosine), cosine}));
        const std::vector<float>&positions = f.positions, &out = f.out;
        const float expected = cosine < 0.9f ? 1.0f : 3.0f;
        int plane = 0, wrong = 0;
        for (std::size_t i = 0; i < out.size(); i += 4)
            if (positions[i + 3] != 0.0f) {
                ++plane;
                wrong += out[i] != expected;
            }
        EXPECT_GT(plane, 1000);
        EXPECT_EQ(wrong, 0) << "plane pixels whose output is not " << expected;
    }
}

// 4. The clamp: a still camera, a history of 100 everywhere, then a current signal that ramps from 1 to
// about 1.6 across the plane. With the clamp the history is pulled to the top of each pixel's 3x3
// neighbourhood of the current signal (the right neighbour's value, the pixel's own at the last column),
// so the output is the mean of the two, within the neighbourhood's range; without it, it is (100 + c) / 2.
TEST_F(TemporalReuseTest, ClampPullsAFarHistoryIntoTheNeighbourhood)
{
    const core::Scene scene = planeScene(false);
    for (bool clamp : {true, false}) {
        SCOPED_TRACE(clamp ? "clamp" : "no clamp");
        gl::Frame frame(scene, smallFrame(64, 32));
        gl::PassTimers timers;
        gl::TemporalReuseSettings settings;
        settings.clamp = clamp;
        gl::TemporalReuse reuse(settings);
        gl::Texture t = makeSignal(64, 32);
        renderGeometry(frame, planeCamera(0.0f), timers);
        const std::vector<float> positions = frame.readPositions();
        upload(t, constantSignal(positions, 100.0f, 0.0f));
        reuse.apply(frame, {&t}, timers);
        renderGeometry(frame, planeCamera(0.0f), timers);
        std::vector<float> ramp(positions.size());
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 64; ++x)
                for (int c = 0; c < 4; ++c) ramp[at(x, y, 64) + c] = c == 3 ? 1.0f : 1.0f + 0.01f * float(x);
        upload(t, ramp);
        reuse.apply(frame, {&t}, timers);
        const std::vector<float> out = t.readFloats(0, 4);
        int checked = 0;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 64; ++x) {
                const std::size_t i = at(x, y, 64);
                if (positions[i + 3] == 0.0f) continue;
                ++checked;
                const float c = ramp[i], top = ramp[at(std::min(x + 1, 63), y, 64)];
                // One rounding of h + (c - h) / 2 off the exact mean: 1 ulp of values about 1.3 or 50.
                if (clamp)
                    EXPECT_NEAR(out[i], 0.5f * (c + top), 1e-6f) << x << "," << y;
                else
                    EXPECT_NEAR(out[i], 0.5f * (c + 100.0f), 1e-5f) << x << "," << y;
            }
        EXPECT_GT(checked, 1000);
    }
}

// 5. NaN and infinity in the history never spread: frame 1's signal holds a NaN and an infinity at two plane
// pixels (the pass passes them through: no history yet); the camera then moves by 1.5 pixels, so that every
// pixel's history is two taps and both bad texels lie in two pixels' footprints. Every output is finite:
// a bad tap is dropped and the other tap taken alone. Clamp on and off: the clamp must not be what hides
// them. Bilinear and Catmull-Rom: the cubic's rows above and below the taps carry no weight on this move
// (it is horizontal), and a bad texel there must not enter it as 0 times NaN.
TEST_F(TemporalReuseTest, NanInHistoryNeverSpreads)
{
    const core::Scene scene = planeScene(false);
    for (int variant = 0; variant < 4; ++variant) {
        const bool clamp = variant & 1, catmullRom = variant & 2;
        SCOPED_TRACE(std::string(clamp ? "clamp" : "no clamp") + (catmullRom ? ", catmull-rom" : ", bilinear"));
        gl::Frame frame(scene, smallFrame(64, 32));
        gl::PassTimers timers;
        gl::TemporalReuseSettings settings;
        settings.clamp = clamp;
        settings.catmullRom = catmullRom;
        gl::TemporalReuse reuse(settings);
        gl::Texture t = makeSignal(64, 32);
        renderGeometry(frame, planeCamera(0.0f), timers);
        std::vector<float> first = worldSignal(frame.readPositions(), 0.0f);
        for (int c = 0; c < 3; ++c) {
            first[at(20, 10, 64) + c] = std::numeric_limits<float>::quiet_NaN();
            first[at(30, 20, 64) + c] = std::numeric_limits<float>::infinity();
        }
        upload(t, first);
        reuse.apply(frame, {&t}, timers);
        renderGeometry(frame, planeCamera(1.5f * pixelOnPlane(32)), timers);
        const std::vector<float> positions = frame.readPositions();
        upload(t, worldSignal(positions, 0.0f));
        reuse.apply(frame, {&t}, timers);
        const std::vector<float> out = t.readFloats(0, 4);
        int bad = 0;
        for (float v : out) bad += !std::isfinite(v);
        EXPECT_EQ(bad, 0) << "values that are not finite";
        // Frame 2's pixel (18 or 19, 10) reads frame 1's (20, 10) as one of its two taps: the other tap
        // alone is its history, worldSignal at frame 1's (21, 10) or (19, 10) (no clamp: exactly that).
        if (!clamp) {
            const std::vector<float> now = worldSignal(positions, 0.0f);
            EXPECT_FLOAT_EQ(out[at(19, 10, 64)], 0.5f * (now[at(19, 10, 64)] + first[at(21, 10, 64)]));
            // The pixels around it whose two taps are finite blend the midpoint of those taps (the signal is
            // linear: the cubic reads what the bilinear blend reads), the bad texel among their outer
            // texels or not.
            for (int y = 8; y <= 12; ++y)
                for (int x = 15; x <= 21; ++x) {
                    const float a = first[at(x + 1, y, 64)], b = first[at(x + 2, y, 64)];
                    if (!std::isfinite(a) || !std::isfinite(b)) continue;
                    EXPECT_NEAR(out[at(x, y, 64)], 0.5f * (now[at(x, y, 64)] + 0.5f * (a + b)), 1e-4f) << x << "," << y;
                }
        }
    }
}

// Reset, a resize and a change in the number of signals drop the history: the next output is the current
// value, even where the history is far from it.
TEST_F(TemporalReuseTest, ResetAndResizeDropTheHistory)
{
    const core::Scene scene = planeScene(false);
    gl::PassTimers timers;
    gl::TemporalReuse reuse(noClamp());
    gl::Frame frame(scene, smallFrame(64, 32));
    gl::Texture t = makeSignal(64, 32), u = makeSignal(64, 32);
    const auto run = [&](gl::Frame& f, gl::Texture& s, float value, const std::vector<gl::Texture*>& signals) {
        renderGeometry(f, planeCamera(0.0f), timers);
        upload(s, constantSignal(f.readPositions(), value, 0.0f));
        if (signals.size() > 1) upload(*signals[1], constantSignal(f.readPositions(), value, 0.0f));
        reuse.apply(f, signals, timers);
        return s.readFloats(0, 4);
    };
    const auto maxAbs = [](const std::vector<float>& v) {
        float m = 0.0f;
        for (float x : v) m = std::max(m, std::abs(x));
        return m;
    };
    EXPECT_FALSE(reuse.hasHistory());
    run(frame, t, 100.0f, {&t});
    EXPECT_TRUE(reuse.hasHistory());
    EXPECT_EQ(maxAbs(run(frame, t, 2.0f, {&t})), 51.0f) << "kept: (100 + 2) / 2";
    // Each drop is checked over two frames: the first passes the signal through, the second shows whether
    // the history it left was the signal (2) or a blend with the old one.
    run(frame, t, 100.0f, {&t});
    reuse.reset();
    EXPECT_FALSE(reuse.hasHistory());
    EXPECT_EQ(maxAbs(run(frame, t, 2.0f, {&t})), 2.0f) << "after reset()";
    EXPECT_EQ(maxAbs(run(frame, t, 2.0f, {&t})), 2.0f) << "the frame after reset()";
    run(frame, t, 100.0f, {&t});
    EXPECT_EQ(maxAbs(run(frame, t, 2.0f, {&t, &u})), 2.0f) << "a second signal";
    EXPECT_EQ(maxAbs(run(frame, t, 2.0f, {&t, &u})), 2.0f) << "the frame after a second signal";
    run(frame, t, 100.0f, {&t, &u});
    gl::Frame larger(scene, smallFrame(37, 23));
    gl::Texture v = makeSignal(37, 23);
    EXPECT_EQ(maxAbs(run(larger, v, 2.0f, {&v})), 2.0f) << "after a resize";
    EXPECT_EQ(maxAbs(run(larger, v, 2.0f, {&v})), 2.0f) << "the frame after a resize";
    EXPECT_THROW(reuse.apply(frame, {&v}, timers), std::invalid_argument) << "a signal of another size";
}

// 7. A still view whose frames jitter (still frames: Frame::beginFrame(true), FrameSampler::jitter): the
// history is kept at pixel centres, so a signal that is the same at each pixel every frame (a checkerboard
// of pixels: what a signal with detail at the pixel's scale looks like) comes back exactly, frame after
// frame. Reprojected through the previous frame's jittered matrix, each frame would read the history a
// jitter's difference away, blend neighbours of the checkerboard and blur it.
TEST_F(TemporalReuseTest, JitteredStillViewKeepsItsHistory)
{
    const core::Scene scene = planeScene(false);
    constexpr int w = 64, h = 32;
    gl::Frame frame(scene, smallFrame(w, h));
    gl::PassTimers timers;
    gl::TemporalReuse reuse(noClamp());
    gl::Texture t = makeSignal(w, h);
    frame.setCamera(planeCamera(0.0f));
    for (int f = 0; f < 6; ++f) {
        frame.beginFrame(f > 0); // frame 0 moving, then still frames 1..5 with their jitter
        frame.renderGBuffer(timers);
        const std::vector<float> positions = frame.readPositions();
        std::vector<float> checker = constantSignal(positions, 1.0f, 0.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if ((x + y) % 2 == 1 && positions[at(x, y, w) + 3] != 0.0f)
                    for (int c = 0; c < 3; ++c) checker[at(x, y, w) + std::size_t(c)] = 3.0f;
        upload(t, checker);
        reuse.apply(frame, {&t}, timers);
        timers.endFrame();
        if (f < 2) continue;
        ASSERT_NE(frame.sampler().jitter(), glm::vec2(0.0f));
        const std::vector<float> out = t.readFloats(0, 4);
        int wrong = 0, plane = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                if (positions[at(x, y, w) + 3] == 0.0f) continue;
                ++plane;
                wrong += out[at(x, y, w)] != checker[at(x, y, w)];
            }
        EXPECT_GT(plane, 1000);
        EXPECT_EQ(wrong, 0) << "plane pixels of still frame " << f << " whose output is not the checkerboard";
    }
}

// The pass is timed as one "temporal" scope with a PassCost, and runs the fragments it declares (one
// full-screen draw per signal; tests/gl/invocations_test.cpp explains the bound): two signals at 37x23,
// with and then without a history. A third draw or a viewport of the wrong size falls outside.
TEST_F(TemporalReuseTest, PassRunsTheFragmentsItDeclares)
{
    const core::Scene scene = planeScene(false);
    gl::Frame frame(scene, smallFrame(37, 23));
    gl::TemporalReuse reuse;
    gl::Texture a = makeSignal(37, 23), b = makeSignal(37, 23);
    for (int f = 0; f < 2; ++f) {
        gl::PassTimers timers;
        frame.setCamera(planeCamera(0.0f));
        frame.beginFrame();
        frame.renderGBuffer(timers);
        upload(a, constantSignal(frame.readPositions(), 1.0f, 0.0f));
        upload(b, constantSignal(frame.readPositions(), 2.0f, 0.0f));
        reuse.apply(frame, {&a, &b}, timers);
        timers.endFrame();
        int found = 0;
        for (const gl::PassStat& p : timers.stats()) {
            if (p.pass != "temporal") continue;
            ++found;
            EXPECT_TRUE(p.work.costDeclared);
            ASSERT_TRUE(p.work.expectedFragmentInvocations);
            EXPECT_EQ(*p.work.expectedFragmentInvocations, 2.0 * 37 * 23);
            if (p.work.fragmentInvocations > 0.0) { // 0 where the driver counts none
                EXPECT_GE(p.work.fragmentInvocations, *p.work.expectedFragmentInvocations);
                EXPECT_LE(p.work.fragmentInvocations, p.work.expectedFragmentInvocationsAtMost);
            }
        }
        EXPECT_EQ(found, 1) << "frame " << f;
    }
}

} // namespace
} // namespace bounce
