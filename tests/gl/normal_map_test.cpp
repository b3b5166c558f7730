// glTF normal maps (core::Material::normalTexture, core::Mesh::tangents) in the G-buffer and in the path
// tracer alike (issue 59):
//   - a closed form: a plane whose map tilts every normal by a known angle, under a directional light, has
//     radiance albedo / pi x E x cos(angle between the bent normal and the light), whatever renders it. The
//     bent normal is computed here from glTF's definition (the texel 2 v - 1 with x, y times the scale, in
//     the basis tangent, w cross(normal, tangent), normal), from the texel's bytes;
//   - the frame parameter normalMaps=0 and core::dropNormalMaps (`bounce reference --no-normal-maps`) give
//     the unbent plane, and a tangent along the normal or a mesh without tangents bend nothing;
//   - a plane with ridges in its map, seen at an angle: the frame's still frames against the path tracer
//     on 4x4-pixel blocks, and the unbent frame clearly further from it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image.h"
#include "core/metrics.h"
#include "core/scene.h"
#include "gl/renderer.h"
#include "ref/reference.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

constexpr float kAlbedo = 0.5f;
constexpr int kSize = 32;

std::uint8_t encode(float v)
{
    return std::uint8_t(std::lround(std::clamp(v * 0.5f + 0.5f, 0.0f, 1.0f) * 255.0f));
}

// A width x height normal map of tangent-space normals n(u, v), u and v at the texels' centres.
template <class F>
core::Texture normalTexture(int width, int height, F n)
{
    core::Texture t;
    t.name = "normals";
    t.width = width;
    t.height = height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec3 v = n((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
            t.rgba8.insert(t.rgba8.end(), {encode(v.x), encode(v.y), encode(v.z), 255});
        }
    return t;
}

// A 2 m square at y = 0 facing +y, its uvs u = (x + 1) / 2 and v = (z + 1) / 2, so that dP/du = +x and the
// image's +y (v decreasing) is -z: tangent (1, 0, 0), and with w = +1 the bitangent w cross(n, t) = -z.
// Lambertian, under a directional light of irradiance 1 W/m^2 from `towardsLight`; the camera 3 m above
// looking down sees nothing else.
core::Scene mappedPlane(const core::Texture& map, glm::vec4 tangent, float scale, glm::vec3 towardsLight)
{
    core::Scene s;
    s.textures.push_back(map);
    core::Material m;
    m.name = "plane";
    m.baseColor = glm::vec3(kAlbedo);
    m.specular = 0.0f;
    m.normalTexture = 0;
    m.normalScale = scale;
    s.materials.push_back(m);
    core::Mesh plane;
    plane.name = "plane";
    plane.positions = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    plane.normals.assign(4, glm::vec3(0, 1, 0));
    for (const glm::vec3& p : plane.positions) plane.uvs.push_back({(p.x + 1.0f) * 0.5f, (p.z + 1.0f) * 0.5f});
    plane.tangents.assign(4, tangent);
    plane.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(plane);
    core::Light sun;
    sun.type = core::LightType::Directional;
    sun.direction = -glm::normalize(towardsLight);
    sun.intensity = glm::vec3(1.0f);
    s.lights.push_back(sun);
    s.camera.position = {0.0f, 3.0f, 0.0f};
    s.camera.forward = {0.0f, -1.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, -1.0f};
    s.camera.yfovRad = 2.0f * std::atan(0.8f / 3.0f); // the middle 1.6 m of the plane fills the image
    return s;
}

// glTF's bent normal for texel bytes `texel`: what both renderers must reproduce.
glm::dvec3 bentNormal(const std::uint8_t* texel, glm::dvec3 tangent, double w, double scale)
{
    const glm::dvec3 n(0, 1, 0);
    glm::dvec3 m = glm::dvec3(texel[0], texel[1], texel[2]) / 255.0 * 2.0 - 1.0;
    m.x *= scale;
    m.y *= scale;
    const glm::dvec3 b = w * glm::cross(n, tangent);
    return glm::normalize(m.x * tangent + m.y * b + m.z * n);
}

double lambert(glm::dvec3 normal, glm::vec3 towardsLight)
{
    return kAlbedo / core::kPi * std::max(0.0, glm::dot(normal, glm::normalize(glm::dvec3(towardsLight))));
}

core::Image glDirect(const core::Scene& scene, bool normalMaps, int frames = 1, int size = kSize, int textureSize = 512)
{
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("normalMaps", normalMaps ? 1 : 0);
    frameValues.setValue("textures.size", textureSize);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), size, size);
    for (int i = 0; i < frames; ++i) r.renderFrame();
    return r.image();
}

core::Image pathTracerDirect(const core::Scene& scene, int spp, int size = kSize)
{
    ref::RenderSettings s;
    s.paths = ref::LightPaths::Direct;
    s.width = s.height = size;
    s.spp = spp;
    s.seed = 5;
    s.progress = false;
    const ref::RenderResult r = ref::render(scene, scene.camera, s);
    EXPECT_EQ(r.nonFiniteSamples, 0u);
    return r.image;
}

// Every pixel of the middle half of `image` (the plane's interior) has radiance `want` (grey), to 1%.
void expectUniform(const core::Image& image, double want, const std::string& what)
{
    int off = 0;
    double worst = 0.0;
    for (int y = kSize / 4; y < 3 * kSize / 4; ++y)
        for (int x = kSize / 4; x < 3 * kSize / 4; ++x) {
            const glm::vec3 v = image.at(x, y);
            for (int c = 0; c < 3; ++c) {
                const double e = std::abs(double(v[c]) - want) / want;
                worst = std::max(worst, e);
                off += e > 0.01;
            }
        }
    std::printf("[ measured ] %s: want %.5f, largest relative difference %.2e\n", what.c_str(), want, worst);
    EXPECT_EQ(off, 0) << what << ": " << off << " channels more than 1% from " << want << " (largest " << worst << ")";
}

struct TiltCase {
    const char* name;
    glm::vec3 texelNormal; // the map's tangent-space normal, everywhere
    glm::vec4 tangent;
    float scale;
    glm::vec3 towardsLight;
};

constexpr float kTilt = 0.6981317f;  // 40 degrees: the map's tilt
constexpr float kLight = 0.5235988f; // 30 degrees: the light's, from the plane's normal

// With the light 30 degrees off the normal towards the tilt, cos 10 degrees; away from it, cos 70; unbent,
// cos 30. Each case tells one convention from its mirror image.
const TiltCase kCases[] = {
    {"towards the tangent",
     {std::sin(kTilt), 0.0f, std::cos(kTilt)},
     {1, 0, 0, 1},
     1.0f,
     {std::sin(kLight), std::cos(kLight), 0.0f}},
    {"towards the bitangent (-z for w = +1)",
     {0.0f, std::sin(kTilt), std::cos(kTilt)},
     {1, 0, 0, 1},
     1.0f,
     {0.0f, std::cos(kLight), -std::sin(kLight)}},
    {"left-handed: the bitangent +z",
     {0.0f, std::sin(kTilt), std::cos(kTilt)},
     {1, 0, 0, -1},
     1.0f,
     {0.0f, std::cos(kLight), -std::sin(kLight)}},
    {"scale 0.5",
     {std::sin(kTilt), 0.0f, std::cos(kTilt)},
     {1, 0, 0, 1},
     0.5f,
     {std::sin(kLight), std::cos(kLight), 0.0f}},
    {"scale 0: unbent",
     {std::sin(kTilt), 0.0f, std::cos(kTilt)},
     {1, 0, 0, 1},
     0.0f,
     {std::sin(kLight), std::cos(kLight), 0.0f}},
    // Hard case: a tangent along the normal spans no tangent plane; nothing is bent (not NaN).
    {"tangent along the normal: unbent",
     {std::sin(kTilt), 0.0f, std::cos(kTilt)},
     {0, 1, 0, 1},
     1.0f,
     {std::sin(kLight), std::cos(kLight), 0.0f}},
};

class NormalMapTest : public GlTest {};

TEST_F(NormalMapTest, TiltedMapGivesLambertOfTheBentNormalInBothRenderers)
{
    for (const TiltCase& c : kCases) {
        const core::Texture map = normalTexture(4, 4, [&](float, float) { return c.texelNormal; });
        const core::Scene scene = mappedPlane(map, c.tangent, c.scale, c.towardsLight);
        const glm::dvec3 t = glm::dvec3(glm::vec3(c.tangent));
        const bool degenerate = std::abs(glm::dot(t, glm::dvec3(0, 1, 0))) > 0.999;
        const glm::dvec3 bent =
            degenerate ? glm::dvec3(0, 1, 0) : bentNormal(map.rgba8.data(), t, c.tangent.w, c.scale);
        const double want = lambert(bent, c.towardsLight);
        SCOPED_TRACE(c.name);
        expectUniform(glDirect(scene, true), want, std::string("frame, ") + c.name);
        expectUniform(pathTracerDirect(scene, 4), want, std::string("path tracer, ") + c.name);
    }
}

// Off together: the frame parameter, and the path tracer's scene without its maps (what `bounce reference
// --no-normal-maps` renders); a mesh without tangents is not bent either.
TEST_F(NormalMapTest, MapsOffAndMeshesWithoutTangentsShadeWithTheVertexNormal)
{
    const TiltCase& c = kCases[0];
    const core::Texture map = normalTexture(4, 4, [&](float, float) { return c.texelNormal; });
    const core::Scene scene = mappedPlane(map, c.tangent, c.scale, c.towardsLight);
    const double unbent = lambert(glm::dvec3(0, 1, 0), c.towardsLight);
    ASSERT_GT(std::abs(lambert(bentNormal(map.rgba8.data(), glm::dvec3(1, 0, 0), 1.0, 1.0), c.towardsLight) - unbent),
              0.1 * unbent)
        << "the map must matter for this test to tell";
    expectUniform(glDirect(scene, false), unbent, "frame, normalMaps=0");
    core::Scene dropped = scene;
    core::dropNormalMaps(dropped);
    EXPECT_NE(dropped.contentHash(), scene.contentHash()) << "cached references of the two must not mix";
    expectUniform(pathTracerDirect(dropped, 4), unbent, "path tracer, without the maps");

    core::Scene bare = scene;
    bare.meshes[0].tangents.clear();
    EXPECT_FALSE(bare.hasNormalMaps());
    expectUniform(glDirect(bare, true), unbent, "frame, a mesh without tangents");
    expectUniform(pathTracerDirect(bare, 4), unbent, "path tracer, a mesh without tangents");
}

// Ridges across the plane (the map's x follows a sine of u, eight periods), lit from the side and seen at an
// angle, so that every pixel's normal differs: the frame's still frames against the path tracer on 4x4-pixel
// blocks. textures.size 64 is the map's own size, so that both sample the same texels bilinearly (a resampled
// map would be the frame's own approximation, not the map).
TEST_F(NormalMapTest, RidgedPlaneMatchesThePathTracer)
{
    constexpr int kRidgeSize = 64, kMapSize = 64;
    const core::Texture map = normalTexture(kMapSize, kMapSize, [](float u, float) {
        const float slope = 0.8f * std::sin(2.0f * core::kPi * 8.0f * u);
        return glm::normalize(glm::vec3(slope, 0.0f, 1.0f));
    });
    core::Scene scene = mappedPlane(map, {1, 0, 0, 1}, 1.0f, {0.6f, 0.8f, 0.0f});
    scene.camera.position = {0.0f, 1.6f, 1.6f};
    scene.camera.forward = glm::normalize(glm::vec3(0.0f, -1.6f, -1.6f));
    scene.camera.up = glm::normalize(glm::vec3(0.0f, 1.6f, -1.6f));
    scene.camera.yfovRad = 0.6f;
    const core::Image reference = core::boxDownsample(pathTracerDirect(scene, 64, kRidgeSize), 16, 16);
    const core::Image mapped = core::boxDownsample(glDirect(scene, true, 16, kRidgeSize, kMapSize), 16, 16);
    const core::Image unbent = core::boxDownsample(glDirect(scene, false, 16, kRidgeSize, kMapSize), 16, 16);
    const double error = core::relativeRmse(mapped, reference), unbentError = core::relativeRmse(unbent, reference);
    std::printf("[ measured ] ridged plane, 4x4-pixel blocks: mapped %.4f, unbent %.4f\n", error, unbentError);
    EXPECT_LT(error, 0.03);
    EXPECT_GT(unbentError, 3.0 * 0.03);
}

} // namespace
} // namespace bounce
