// GL queries (gl/resource/query.h) against counts known in closed form: samples passed by a quad with
// pixel-aligned edges is its pixel count, primitives generated is the number of triangles drawn (clipped
// or not).
#include <gtest/gtest.h>

#include "gl/gl.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/query.h"
#include "gl/resource/texture.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class QueryTest : public GlTest {
protected:
    void SetUp() override
    {
        GlTest::SetUp();
        program_ = gl::Program::graphics("test.query.rect", "test/rect.vert", "test/flat.frag");
        vao_ = gl::VertexArray("test.query.vao");
    }

    // A width x height colour target, bound, with the viewport over all of it.
    void target(int width, int height)
    {
        colour_ = gl::Texture::create2D("test.query.colour", GL_RGBA8, width, height);
        fbo_ = gl::Framebuffer("test.query.fbo");
        fbo_.attach(GL_COLOR_ATTACHMENT0, colour_);
        fbo_.checkComplete();
        fbo_.bind();
        glViewport(0, 0, width, height);
        width_ = width;
        height_ = height;
    }

    // Draws `quads` copies of the pixel rectangle [x0, x1) x [y0, y1) (two triangles each).
    void drawPixelRect(int x0, int y0, int x1, int y1, int quads = 1)
    {
        const auto ndc = [](int p, int size) { return 2.0f * float(p) / float(size) - 1.0f; };
        program_.set("rect", glm::vec4(ndc(x0, width_), ndc(y0, height_), ndc(x1, width_), ndc(y1, height_)));
        program_.use();
        vao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 6 * quads);
    }

    gl::Program program_;
    gl::VertexArray vao_;
    gl::Texture colour_;
    gl::Framebuffer fbo_;
    int width_ = 0, height_ = 0;
};

// Pixel centres (x + 0.5, y + 0.5) inside a rectangle with integer edges: exactly (x1 - x0)(y1 - y0)
// of them, whatever the rasteriser's tie rule (no centre lies on an edge). Also the 1x1 and 3x5
// viewports, covered whole.
TEST_F(QueryTest, SamplesPassedIsThePixelCount)
{
    target(64, 48);
    gl::Query samples(GL_SAMPLES_PASSED, "test.query.samples");
    {
        auto scope = samples.scope();
        drawPixelRect(10, 5, 42, 30);
    }
    EXPECT_EQ(samples.result(), 32u * 25u);

    for (const glm::ivec2 size : {glm::ivec2(1, 1), glm::ivec2(3, 5)}) {
        target(size.x, size.y);
        samples.begin();
        drawPixelRect(0, 0, size.x, size.y);
        samples.end();
        EXPECT_EQ(samples.result(), std::uint64_t(size.x * size.y)) << size.x << "x" << size.y;
    }
}

// Primitives generated counts what the vertex stage emits, before clipping: 14 triangles inside, and 6
// wholly outside the clip volume that pass no sample.
TEST_F(QueryTest, PrimitivesGeneratedIsTheTriangleCount)
{
    target(32, 32);
    gl::Query primitives(GL_PRIMITIVES_GENERATED, "test.query.primitives");
    gl::Query samples(GL_SAMPLES_PASSED, "test.query.samples");
    {
        auto p = primitives.scope();
        drawPixelRect(0, 0, 16, 16, 7);
    }
    EXPECT_EQ(primitives.result(), 14u);
    {
        auto p = primitives.scope();
        auto s = samples.scope();
        drawPixelRect(40, 40, 50, 50, 3); // x and y beyond the viewport's right and top edges
    }
    EXPECT_EQ(primitives.result(), 6u);
    EXPECT_EQ(samples.result(), 0u);
}

TEST_F(QueryTest, TimeElapsedEndsWithAResult)
{
    target(8, 8);
    gl::Query time(GL_TIME_ELAPSED, "test.query.time");
    {
        auto t = time.scope();
        glClear(GL_COLOR_BUFFER_BIT);
    }
    (void)time.result(); // nanoseconds; never compared with anything (no timings in tests)
    EXPECT_TRUE(time.resultAvailable());
}

TEST_F(QueryTest, MisuseIsRefused)
{
    gl::Query q(GL_SAMPLES_PASSED, "test.query.misuse");
    EXPECT_THROW((void)q.result(), gl::QueryError);
    EXPECT_FALSE(q.resultAvailable());
    EXPECT_THROW(q.end(), gl::QueryError);
    q.begin();
    EXPECT_THROW(q.begin(), gl::QueryError);
    EXPECT_THROW((void)q.result(), gl::QueryError);
    q.end();
    gl::Query moved = std::move(q);
    EXPECT_FALSE(q);
    EXPECT_TRUE(moved);
    EXPECT_THROW(q.begin(), gl::QueryError);
}

} // namespace
} // namespace bounce
