// The compute-dispatch helpers (gl/resource/dispatch.h): every invocation inside the size runs once, the
// partial groups hold exactly the remainder, a dispatch in rows reaches every group past one axis's limit,
// bad sizes are refused before GL sees them.
#include <algorithm>
#include <climits>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "gl/gl.h"
#include "gl/resource/buffer.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/program.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class DispatchTest : public GlTest {
protected:
    // Dispatches `size` with `local`, returns the count of every cell inside and the count outside.
    static std::pair<std::vector<std::uint32_t>, std::uint32_t> run(glm::ivec3 size, glm::ivec3 local)
    {
        gl::Program prog = program(local);
        const std::size_t cells = std::size_t(size.x) * size.y * size.z;
        gl::Buffer buffer = gl::Buffer::fromVector("test.dispatch.cells", std::vector<std::uint32_t>(cells + 1, 0u));
        buffer.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
        prog.set("size", size);
        gl::dispatchCompute(prog, size, local);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<std::uint32_t> all = buffer.download<std::uint32_t>();
        const std::uint32_t outside = all.front();
        all.erase(all.begin());
        return {all, outside};
    }

    static gl::Program program(glm::ivec3 local)
    {
        return gl::Program::compute("test.dispatch", "test/dispatch_cover.comp",
                                    {{"LOCAL_X", std::to_string(local.x)},
                                     {"LOCAL_Y", std::to_string(local.y)},
                                     {"LOCAL_Z", std::to_string(local.z)}});
    }
};

TEST(DispatchGroups, CeilingOfSizeOverLocalSize)
{
    EXPECT_EQ(gl::computeGroupCount({3, 5, 1}, {8, 8, 1}), glm::ivec3(1, 1, 1));
    EXPECT_EQ(gl::computeGroupCount({1, 1, 1}, {8, 8, 1}), glm::ivec3(1, 1, 1));
    EXPECT_EQ(gl::computeGroupCount({16, 17, 3}, {8, 8, 2}), glm::ivec3(2, 3, 2));
    EXPECT_EQ(gl::computeGroupCount({INT_MAX, 1, 1}, {1, 1, 1}), glm::ivec3(INT_MAX, 1, 1)); // no overflow
    EXPECT_THROW(gl::computeGroupCount({0, 5, 1}, {8, 8, 1}), gl::DispatchError);
    EXPECT_THROW(gl::computeGroupCount({3, -5, 1}, {8, 8, 1}), gl::DispatchError);
    EXPECT_THROW(gl::computeGroupCount({3, 5, 1}, {8, 0, 1}), gl::DispatchError);
}

// 3x5 and 1x1 in 8x8 groups (one partial group), 17x9x3 in 4x4x2 groups (partial on every axis): every
// cell exactly once, and the invocations outside exactly the rest of the groups launched.
TEST_F(DispatchTest, EveryInvocationInsideOnceNothingElse)
{
    for (const auto& [size, local] :
         {std::pair{glm::ivec3(3, 5, 1), glm::ivec3(8, 8, 1)}, std::pair{glm::ivec3(1, 1, 1), glm::ivec3(8, 8, 1)},
          std::pair{glm::ivec3(17, 9, 3), glm::ivec3(4, 4, 2)}}) {
        const auto [cells, outside] = run(size, local);
        std::size_t wrong = 0;
        for (std::uint32_t c : cells) wrong += c != 1u;
        EXPECT_EQ(wrong, 0u) << size.x << "x" << size.y << "x" << size.z << ": cells not written exactly once";
        const glm::ivec3 launched = ((size + local - 1) / local) * local;
        EXPECT_EQ(outside, std::uint32_t(launched.x * launched.y * launched.z - size.x * size.y * size.z))
            << size.x << "x" << size.y << "x" << size.z;
    }
}

// dispatchRows: 5 groups in one row, 2 x 65,535 + 3 groups in three rows (past the least per-axis limit a
// driver may have), none: every group inside once, and the rest of the last row exactly what runs past it.
TEST_F(DispatchTest, RowsReachEveryGroupOncePastOneAxisLimit)
{
    gl::Program prog = gl::Program::compute("test.dispatchRows", "test/dispatch_rows.comp");
    for (const std::size_t groups : {std::size_t(5), 2 * gl::kMaxRowGroups + 3, std::size_t(0)}) {
        gl::Buffer buffer = gl::Buffer::fromVector("test.dispatch.rows", std::vector<std::uint32_t>(groups + 1, 0u));
        buffer.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
        prog.set("groups", unsigned(groups));
        gl::dispatchRows(prog, groups, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const std::vector<std::uint32_t> all = buffer.download<std::uint32_t>();
        std::size_t wrong = 0;
        for (std::size_t g = 1; g < all.size(); ++g) wrong += all[g] != 1u;
        EXPECT_EQ(wrong, 0u) << groups << " groups: groups not run exactly once";
        const std::size_t row = std::min(std::max(groups, std::size_t(1)), gl::kMaxRowGroups);
        const std::size_t launched = groups == 0 ? 0 : (groups + row - 1) / row * row;
        EXPECT_EQ(all.front(), std::uint32_t(launched - groups)) << groups << " groups: runs past the count";
    }
}

// A program whose storage block has no buffer under its name reads nothing: the dispatch is refused, naming
// the block; with a buffer bound it runs. The buffer bound and then deleted is bound under no name.
TEST_F(DispatchTest, RefusesAProgramWithUnboundStorage)
{
    gl::Program prog = gl::Program::compute("test.dispatchRows", "test/dispatch_rows.comp");
    prog.set("groups", 1u);
    {
        gl::Buffer gone("test.dispatch.gone", 16);
        gone.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    }
    try {
        gl::dispatchRows(prog, 1, 1);
        ADD_FAILURE() << "a dispatch with nothing bound under its block's name was accepted";
    } catch (const gl::DispatchError& e) {
        EXPECT_NE(std::string(e.what()).find("Cells"), std::string::npos) << e.what();
    }
    gl::Buffer buffer = gl::Buffer::fromVector("test.dispatch.bound", std::vector<std::uint32_t>(2, 0u));
    buffer.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    EXPECT_NO_THROW(gl::dispatchRows(prog, 1, 1));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    EXPECT_EQ(buffer.download<std::uint32_t>()[1], 1u);
}

TEST_F(DispatchTest, RefusesBadSizes)
{
    gl::Program prog = program({8, 8, 1});
    EXPECT_THROW(gl::dispatchCompute(prog, {0, 1, 1}, {8, 8, 1}), gl::DispatchError);
    EXPECT_THROW(gl::dispatchCompute(prog, {4, -1, 1}, {8, 8, 1}), gl::DispatchError);
    try {
        gl::dispatchCompute(prog, {4, 4, 1}, {4, 4, 1});
        ADD_FAILURE() << "a local size other than the program's was accepted";
    } catch (const gl::DispatchError& e) {
        EXPECT_NE(std::string(e.what()).find("8x8x1"), std::string::npos) << e.what();
    }
    GLint most = 0;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 1, &most);
    ASSERT_GT(most, 0);
    try {
        gl::dispatchCompute(prog, {8, most * 8 + 1, 1}, {8, 8, 1});
        ADD_FAILURE() << "a dispatch over GL_MAX_COMPUTE_WORK_GROUP_COUNT was accepted";
    } catch (const gl::DispatchError& e) {
        EXPECT_NE(std::string(e.what()).find("GL_MAX_COMPUTE_WORK_GROUP_COUNT"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace bounce
