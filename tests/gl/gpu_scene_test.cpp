// The scene on the GPU as any shader reads it (glsl/common/scene.glsl, SCENE_GEOMETRY) against core::Scene
// on the CPU: every triangle's corners, material, a point and normal inside it, and the emissive
// triangles with their areas and power CDF.
#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/frame/gpu_scene.h"
#include "gl/gl.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class GpuSceneTest : public GlTest {
protected:
    struct Read {
        std::vector<glm::vec4> triangles, emitters;
    };
    Read read(const core::Scene& scene, glm::vec2 b)
    {
        gl::GpuScene gpu(scene, 1);
        const std::size_t n = scene.triangleCount();
        gl::Buffer triangles("test.triangles", std::max<std::size_t>(n, 1) * 6 * sizeof(glm::vec4));
        gl::Buffer emitters("test.emitters", (1 + n) * sizeof(glm::vec4));
        gl::Program prog = gl::Program::compute("test.sceneGeometry", "test/scene_geometry.comp");
        gpu.bindGeometry();
        // test/scene_geometry.comp's storage names, SSBO_TEST_TRIANGLES and SSBO_TEST_EMITTERS: under 0 and 1
        // they would be the scene's materials and lights, which the shader declares too.
        triangles.bindBase(GL_SHADER_STORAGE_BUFFER, 1010);
        emitters.bindBase(GL_SHADER_STORAGE_BUFFER, 1011);
        prog.set("barycentrics", b);
        prog.use();
        glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        return {triangles.download<glm::vec4>(), emitters.download<glm::vec4>()};
    }
};

TEST_F(GpuSceneTest, TrianglesAndEmittersMatchTheCpuScene)
{
    for (const char* name : {"cornell-area", "cornell-spot"}) {
        SCOPED_TRACE(name);
        const core::Scene scene = core::makeCornell(name);
        const glm::vec2 b(0.2f, 0.3f);
        const Read r = read(scene, b);
        ASSERT_EQ(std::size_t(r.emitters[0].z), scene.triangleCount());

        std::size_t t = 0;
        std::vector<std::size_t> emissive;
        double power = 0.0;
        for (const core::Mesh& m : scene.meshes)
            for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3, ++t) {
                glm::vec3 p[3];
                for (int k = 0; k < 3; ++k) {
                    p[k] = m.positions[m.indices[i + k]];
                    EXPECT_EQ(glm::vec3(r.triangles[6 * t + k]), p[k]) << "triangle " << t << " corner " << k;
                }
                EXPECT_EQ(std::uint32_t(r.triangles[6 * t + 3].x), m.material) << "triangle " << t;
                const glm::vec3 point = (1.0f - b.x - b.y) * p[0] + b.x * p[1] + b.y * p[2];
                EXPECT_LT(glm::length(glm::vec3(r.triangles[6 * t + 4]) - point), 1e-5f) << "triangle " << t;
                const glm::vec3 n =
                    glm::normalize((1.0f - b.x - b.y) * m.normals[m.indices[i]] + b.x * m.normals[m.indices[i + 1]] +
                                   b.y * m.normals[m.indices[i + 2]]);
                EXPECT_LT(glm::length(glm::vec3(r.triangles[6 * t + 5]) - n), 1e-5f) << "triangle " << t;
                const core::Material& mat = scene.materials[m.material];
                if (mat.isEmissive()) {
                    emissive.push_back(t);
                    const double lum = 0.2126 * mat.emission.x + 0.7152 * mat.emission.y + 0.0722 * mat.emission.z;
                    power += core::kPi * lum * 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
                }
            }
        ASSERT_EQ(std::size_t(r.emitters[0].x), emissive.size());
        EXPECT_NEAR(r.emitters[0].y, power, 1e-5 * power);
        float previousCdf = 0.0f;
        for (std::size_t e = 0; e < emissive.size(); ++e) {
            const glm::vec4 got = r.emitters[1 + e];
            EXPECT_EQ(std::size_t(got.x), emissive[e]);
            EXPECT_GT(got.w, previousCdf); // increasing
            previousCdf = got.w;
        }
        if (!emissive.empty()) {
            EXPECT_EQ(previousCdf, 1.0f);
        }
    }
}

// A degenerate emitter (three corners on one line) has no area: it is left out of the emitter list
// rather than given a zero-width CDF step that sampling could still land on.
TEST_F(GpuSceneTest, DegenerateEmitterIsLeftOut)
{
    core::Scene scene = core::makeCornell("cornell-area");
    core::Mesh line;
    line.name = "degenerate emitter";
    line.positions = {{0, 0.5f, 0}, {0.1f, 0.5f, 0}, {0.2f, 0.5f, 0}};
    line.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
    line.indices = {0, 1, 2};
    std::uint32_t emitterMaterial = 0;
    for (std::uint32_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].isEmissive()) emitterMaterial = i;
    line.material = emitterMaterial;
    const std::size_t before = read(scene, {0.3f, 0.3f}).emitters[0].x;
    scene.meshes.push_back(line);
    const Read r = read(scene, {0.3f, 0.3f});
    EXPECT_EQ(std::size_t(r.emitters[0].x), before);
    EXPECT_EQ(std::size_t(r.emitters[0].z), scene.triangleCount());
}

} // namespace
} // namespace bounce
