// The reference against closed forms: a Lambertian plane under a point light, under a directional
// light and under a square area light (per pixel, averaged over the pixel's footprint as the box filter
// does), the edge of a hard spot cone, the white furnace for every light-path selection, and the
// one-sidedness rules. Tolerances follow from the sample count through the renderer's own per-pixel
// variance estimate, plus the stated quadrature error of the expected value.
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "tests/image_expect.h"
#include "tests/ref/test_scenes.h"

namespace {

using namespace bounce;
using namespace bounce::testing;
using ref::LightPaths;

// The ground point seen through image position (px, py) by a camera looking down at the plane y = 0.
glm::dvec3 groundPoint(const core::Camera& cam, double px, double py, int w, int h)
{
    const glm::dvec3 d(cam.rayDirection(float(px), float(py), w, h));
    const glm::dvec3 o(cam.position);
    return o + d * (-o.y / d.y);
}

// Mean and spread of radiance(x, z) over the footprint of each pixel (sub x sub midpoint samples).
struct Expected {
    core::Image mean, spread; // spread: the standard deviation of radiance inside the pixel
};

Expected pixelAverages(const core::Camera& cam, int w, int h, const std::function<glm::dvec3(double, double)>& radiance)
{
    const int sub = 8;
    Expected e{core::Image(w, h), core::Image(w, h)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::dvec3 sum(0.0), sum2(0.0);
            for (int j = 0; j < sub; ++j)
                for (int i = 0; i < sub; ++i) {
                    const glm::dvec3 p = groundPoint(cam, x + (i + 0.5) / sub, y + (j + 0.5) / sub, w, h);
                    const glm::dvec3 l = radiance(p.x, p.z);
                    sum += l;
                    sum2 += l * l;
                }
            const glm::dvec3 mean = sum / double(sub * sub);
            e.mean.set(x, y, glm::vec3(mean));
            e.spread.set(x, y, glm::vec3(glm::sqrt(glm::max(sum2 / double(sub * sub) - mean * mean, 0.0))));
        }
    return e;
}

core::Scene groundPlane(float albedo)
{
    core::Scene s;
    const auto m = addMaterial(s, lambertian(glm::vec3(albedo)));
    addHorizontalSquare(s, m, 0.0f, 20.0f, true);
    return s;
}

// Per pixel: |render - expected| <= 5 sigma of the render (its own variance estimate, floored by the
// footprint spread / sqrt(spp) for estimators whose only noise is the pixel jitter) + 0.5% of expected
// for the midpoint rule. Also the image means agree to 0.5%.
void expectMatches(const ref::RenderResult& r, const Expected& e, const char* what)
{
    int bad = 0;
    for (int y = 0; y < r.image.height; ++y)
        for (int x = 0; x < r.image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float got = r.image.at(x, y)[c], want = e.mean.at(x, y)[c];
                const float sigma =
                    std::max(std::sqrt(r.variance.at(x, y)[c]), e.spread.at(x, y)[c] / std::sqrt(float(r.spp)));
                if (std::abs(got - want) > 5.0f * sigma + 0.005f * want + 1e-7f && bad++ < 5)
                    ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") channel " << c << ": " << got
                                  << " expected " << want << " sigma " << sigma;
            }
    EXPECT_EQ(bad, 0) << what;
    const std::string name = std::string("analytic-") + what;
    const double meanError = bounce::testing::expectImagesClose(
        name, r.image, e.mean, bounce::testing::ImageMetric::meanRelative(), 0.005, "the midpoint rule's 0.5%");
    // The per-pixel bound above is the test's own; the images on its failure come from the same place.
    if (bad > 0 && meanError <= 0.005) bounce::testing::writeComparisonImages(name, r.image, e.mean);
}

TEST(Analytic, LambertianPlaneUnderPointLight)
{
    // L = rho / pi * I cos(theta) / r^2 = rho I h / (pi r^3) for a light at height h above (0, 0).
    const float rho = 0.6f, height = 1.0f;
    const glm::vec3 intensity(2.0f, 1.0f, 0.5f);
    core::Scene s = groundPlane(rho);
    core::Light l;
    l.type = core::LightType::Point;
    l.position = {0.0f, height, 0.0f};
    l.intensity = intensity;
    s.lights.push_back(l);
    const core::Camera cam = cameraLookingDown({0.1f, 2.0f, 0.0f}, glm::radians(60.0f));
    const int size = 32;
    const Expected e = pixelAverages(cam, size, size, [&](double x, double z) {
        const double r = std::sqrt(x * x + z * z + double(height) * height);
        return glm::dvec3(intensity) * (rho * height / (3.14159265358979323846 * r * r * r));
    });
    for (LightPaths paths : {LightPaths::Direct, LightPaths::Full}) { // nothing else to bounce off: equal
        const ref::RenderResult r = ref::render(s, cam, settings(paths, size, 16));
        expectMatches(r, e, ("point-light-" + ref::lightPathsName(paths)).c_str());
    }
}

TEST(Analytic, LambertianPlaneUnderDirectionalLight)
{
    // L = rho / pi * E cos(theta), uniform.
    const float rho = 0.5f;
    core::Scene s = groundPlane(rho);
    core::Light l;
    l.type = core::LightType::Directional;
    l.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    l.intensity = glm::vec3(3.0f);
    s.lights.push_back(l);
    const core::Camera cam = cameraLookingDown({0.0f, 1.0f, 0.0f}, glm::radians(40.0f));
    const ref::RenderResult r = ref::render(s, cam, settings(LightPaths::Direct, 16, 2));
    const float expected = rho / core::kPi * 3.0f * -l.direction.y;
    for (float v : r.image.rgb) ASSERT_NEAR(v, expected, 1e-5f * expected);
}

// Irradiance at the origin of a plane from a parallel Lambertian rectangle of unit radiance spanning
// [0, a] x [0, b] at height h (the corner above the point), signed for negative a, b: pi times the
// point-to-parallel-rectangle form factor (e.g. Howell's catalogue of configuration factors, B-3).
double cornerIrradiance(double a, double b, double h)
{
    const double A = a / h, B = b / h;
    const double sa = std::sqrt(1.0 + A * A), sb = std::sqrt(1.0 + B * B);
    return 0.5 * (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb));
}

TEST(Analytic, LambertianPlaneUnderSquareAreaLight)
{
    // A 0.6 m square emitter facing down at height 0.5, centred above (0.1, 0); the camera hangs
    // between them (below the emitter, whose back it cannot see: the back of an emitter is black).
    const float rho = 0.7f, height = 0.5f, half = 0.3f, cx = 0.1f;
    const glm::vec3 le(1.0f, 2.0f, 3.0f);
    core::Scene s = groundPlane(rho);
    const auto light = addMaterial(s, lambertian(glm::vec3(0.0f), le));
    addHorizontalSquare(s, light, height, half, false, cx, 0.0f);
    const core::Camera cam = cameraLookingDown({0.0f, 0.3f, 0.0f}, glm::radians(70.0f));
    const int size = 24;
    const Expected e = pixelAverages(cam, size, size, [&](double x, double z) {
        const double x0 = cx - half - x, x1 = cx + half - x, z0 = -half - z, z1 = half - z;
        const double irradiance = cornerIrradiance(x1, z1, height) - cornerIrradiance(x0, z1, height) -
                                  cornerIrradiance(x1, z0, height) + cornerIrradiance(x0, z0, height);
        return glm::dvec3(le) * (rho / 3.14159265358979323846 * irradiance);
    });
    ASSERT_GT(imageMean(e.mean), 0.1);
    const ref::RenderResult r = ref::render(s, cam, settings(LightPaths::Direct, size, 64));
    expectMatches(r, e, "area-light");
}

TEST(Analytic, SpotConeEdgeIsWhereGeometryPutsIt)
{
    // A hard 30-degree cone from 1 m up lights the disk of radius tan(30 deg). Pixels whose whole
    // footprint is inside are lit (to the closed form of a point light), pixels wholly outside are exactly 0.
    const float rho = 0.5f, height = 1.0f, halfAngle = glm::radians(30.0f);
    core::Scene s = groundPlane(rho);
    core::Light l;
    l.type = core::LightType::Spot;
    l.position = {0.0f, height, 0.0f};
    l.direction = {0.0f, -1.0f, 0.0f};
    l.innerConeRad = l.outerConeRad = halfAngle;
    l.intensity = glm::vec3(1.0f);
    s.lights.push_back(l);
    const core::Camera cam = cameraLookingDown({0.0f, 2.0f, 0.0f}, 2.0f * std::atan(0.5f));
    const int size = 64;
    const ref::RenderResult r = ref::render(s, cam, settings(LightPaths::Direct, size, 8));
    const double radius = std::tan(double(halfAngle));
    int inside = 0, outside = 0, edge = 0, edgeLit = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double rMin = 1e9, rMax = 0.0;
            for (int j = 0; j <= 8; ++j)
                for (int i = 0; i <= 8; ++i) { // the footprint's boundary and interior, finely
                    const glm::dvec3 p = groundPoint(cam, x + i / 8.0, y + j / 8.0, size, size);
                    const double rr = std::sqrt(p.x * p.x + p.z * p.z);
                    rMin = std::min(rMin, rr);
                    rMax = std::max(rMax, rr);
                }
            const float v = r.image.at(x, y).x;
            if (rMax < radius) {
                ++inside;
                // Point-light closed form at the footprint's nearest and farthest radii bound the pixel.
                const auto lr = [&](double rr) {
                    return rho * height / (core::kPi * std::pow(rr * rr + height * height, 1.5));
                };
                EXPECT_GE(v, lr(rMax) * 0.999) << x << ", " << y;
                EXPECT_LE(v, lr(rMin) * 1.001) << x << ", " << y;
            } else if (rMin > radius) {
                ++outside;
                EXPECT_EQ(v, 0.0f) << x << ", " << y;
            } else {
                ++edge;
                edgeLit += v > 0.0f; // 8 jittered samples may all miss a sliver of the disk
            }
        }
    EXPECT_GT(inside, 1000);
    EXPECT_GT(outside, 1000);
    EXPECT_GT(edge, 50);
    EXPECT_GT(edgeLit, edge / 2);
}

// The white furnace: inside a closed enclosure of albedo a emitting Le everywhere, radiance is
// Le (1 + a + ... + a^k) over paths of up to k reflections, Le / (1 - a) over all of them, whatever the
// shape. The sphere here is flat triangles facing inwards, the camera at its centre. In a convex
// enclosure nothing occludes, so the no-visibility paths equal the visible ones.
TEST(Analytic, WhiteFurnaceEveryLightPath)
{
    const float a = 0.5f;
    const glm::vec3 le(1.0f, 0.5f, 2.0f);
    core::Scene s;
    const auto m = addMaterial(s, lambertian(glm::vec3(a), le));
    addInwardSphere(s, m, 1.0f, 12, 24);
    core::Camera cam;
    cam.position = glm::vec3(0.05f, -0.02f, 0.03f);
    cam.yfovRad = glm::radians(90.0f);
    const struct {
        LightPaths paths;
        double factor;
        int spp;
    } cases[] = {
        {LightPaths::Direct, 1.0 + a, 16},
        {LightPaths::OneBounce, 1.0 + a + a * a, 16},
        {LightPaths::OneBounceIndirect, a * a, 16},
        {LightPaths::OneBounceNoVis, 1.0 + a + a * a, 16},
        {LightPaths::OneBounceNoVisIndirect, a * a, 16},
        {LightPaths::Full, 1.0 / (1.0 - a), 32},
    };
    for (const auto& c : cases) {
        const ref::RenderResult r = ref::render(s, cam, settings(c.paths, 16, c.spp));
        for (int ch = 0; ch < 3; ++ch) {
            const double want = le[ch] * c.factor;
            const double se = imageMeanStdErr(r.variance) * std::sqrt(3.0); // per channel: a third of the values
            EXPECT_NEAR(imageMean(r.image, ch), want, 5.0 * se + 1e-4 * want)
                << ref::lightPathsName(c.paths) << " channel " << ch;
        }
        EXPECT_EQ(r.nonFiniteSamples, 0u);
    }
}

TEST(Analytic, FurnaceWithMaxDepthTruncatesTheSeries)
{
    const float a = 0.6f;
    core::Scene s;
    const auto m = addMaterial(s, lambertian(glm::vec3(a), glm::vec3(1.0f)));
    addInwardSphere(s, m, 1.0f, 8, 16);
    core::Camera cam;
    cam.yfovRad = glm::radians(90.0f);
    ref::RenderSettings rs = settings(LightPaths::Full, 12, 32);
    rs.maxDepth = 3;
    const ref::RenderResult r = ref::render(s, cam, rs);
    const double want = 1.0 + a + a * a + a * a * a;
    EXPECT_NEAR(imageMean(r.image), want, 5.0 * imageMeanStdErr(r.variance) + 1e-4);
}

TEST(Analytic, BackOfOneSidedSurfaceIsBlackUnlessDoubleSided)
{
    // A plane facing down, lit from above and seen from above: one-sided it is black; double-sided it
    // shades like a plane facing up.
    for (bool doubleSided : {false, true}) {
        core::Scene s;
        core::Material mat = lambertian(glm::vec3(0.5f));
        mat.doubleSided = doubleSided;
        const auto m = addMaterial(s, mat);
        addHorizontalSquare(s, m, 0.0f, 10.0f, false);
        core::Light l;
        l.type = core::LightType::Directional;
        l.direction = {0.0f, -1.0f, 0.0f};
        l.intensity = glm::vec3(2.0f);
        s.lights.push_back(l);
        const ref::RenderResult r =
            ref::render(s, cameraLookingDown({0, 1, 0}, 0.5f), settings(LightPaths::Full, 8, 2));
        const float expected = doubleSided ? 0.5f / core::kPi * 2.0f : 0.0f;
        for (float v : r.image.rgb) ASSERT_NEAR(v, expected, 1e-5f) << (doubleSided ? "double-sided" : "one-sided");
    }
}

TEST(Analytic, EmitterBackIsBlackAndOpaque)
{
    // Seen from above, an emitter facing down shows its black back and hides the lit plane below it.
    core::Scene s = groundPlane(0.5f);
    const auto light = addMaterial(s, lambertian(glm::vec3(0.0f), glm::vec3(5.0f)));
    addHorizontalSquare(s, light, 0.5f, 5.0f, false);
    const ref::RenderResult r = ref::render(s, cameraLookingDown({0, 1, 0}, 0.5f), settings(LightPaths::Full, 8, 4));
    for (float v : r.image.rgb) ASSERT_EQ(v, 0.0f);
    // From below, it shines with its radiance.
    core::Camera up;
    up.position = {0.0f, 0.2f, 0.0f};
    up.forward = {0.0f, 1.0f, 0.0f};
    up.up = {0.0f, 0.0f, 1.0f};
    up.yfovRad = 0.5f;
    const ref::RenderResult r2 = ref::render(s, up, settings(LightPaths::Direct, 8, 4));
    for (float v : r2.image.rgb) ASSERT_NEAR(v, 5.0f, 1e-6f);
}

} // namespace
