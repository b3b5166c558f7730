// Storage blocks bound by name, per program (gl/resource/storage_bindings.h): the names come out of the
// layouts, each program numbers its own binding points, what a program reads under a name is what was last
// bound under it whatever other programs ran between, two blocks under one name fail to link, and a name
// nothing bound reads no buffer.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/gl.h"
#include "gl/resource/buffer.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/program.h"
#include "gl/resource/storage_bindings.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

TEST(StorageNames, TakenFromTheLayouts)
{
    const std::string source = "#version 450 core\n"
                               "#define SSBO_A 40\n"
                               "#define SSBO_B SSBO_A_TOO\n"
                               "#define SSBO_A_TOO 41\n"
                               "layout(std430, binding = SSBO_A) readonly buffer Alpha { uint a[]; };\n"
                               "layout(binding = SSBO_B, std430) buffer Beta { uint b[]; };\n"
                               "layout(binding = 7) coherent buffer Gamma { uint c[]; };\n"
                               "layout(std140, binding = 3) uniform Camera { mat4 m; };\n"
                               "layout(local_size_x = 64) in;\n";
    gl::StorageNames names;
    const std::string out = gl::takeStorageNames(source, "test", names);
    EXPECT_EQ(names, (gl::StorageNames{{"Alpha", 40u}, {"Beta", 41u}, {"Gamma", 7u}}));
    EXPECT_NE(out.find("layout(std430) readonly buffer Alpha"), std::string::npos) << out;
    EXPECT_NE(out.find("layout(std430) buffer Beta"), std::string::npos) << out;
    EXPECT_NE(out.find("\n coherent buffer Gamma"), std::string::npos) << out;
    EXPECT_NE(out.find("layout(std140, binding = 3) uniform Camera"), std::string::npos)
        << "a uniform block keeps its unit";
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), std::count(source.begin(), source.end(), '\n'));
}

TEST(StorageNames, MistakesAreShaderErrors)
{
    gl::StorageNames names;
    EXPECT_THROW(gl::takeStorageNames("layout(std430) buffer A { uint a[]; };\n", "test", names), gl::ShaderError);
    EXPECT_THROW(
        gl::takeStorageNames("layout(std430, binding = SSBO_NOWHERE) buffer A { uint a[]; };\n", "test", names),
        gl::ShaderError);
    // One name defined twice (in two branches): which one the compiler takes is not known here.
    EXPECT_THROW(gl::takeStorageNames("#define SSBO_X 1\n#define SSBO_X 2\n"
                                      "layout(std430, binding = SSBO_X) buffer A { uint a[]; };\n",
                                      "test", names),
                 gl::ShaderError);
    // One block under two names in one program.
    gl::StorageNames twice;
    gl::takeStorageNames("layout(std430, binding = 1) buffer A { uint a[]; };\n", "vertex", twice);
    EXPECT_THROW(gl::takeStorageNames("layout(std430, binding = 2) buffer A { uint a[]; };\n", "fragment", twice),
                 gl::ShaderError);
}

class StorageBindingsTest : public GlTest {
protected:
    static gl::Program copy(const std::string& target, bool onlyTarget = false)
    {
        std::vector<gl::Define> defines{{"TARGET_NAME", target}};
        if (onlyTarget) defines.push_back({"ONLY_TARGET", "1"});
        return gl::Program::compute("test.storageNames", "test/storage_names.comp", defines);
    }
    static void run(const gl::Program& p, std::uint32_t count, std::uint32_t factor)
    {
        gl::Program& q = const_cast<gl::Program&>(p);
        q.set("count", count);
        q.set("factor", factor);
        gl::dispatchCompute(p, {int(count), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }
};

// Names past every driver's count of binding points; each program numbers its blocks from 0, so one name
// sits at different points in two programs, and each reads its own buffers.
TEST_F(StorageBindingsTest, EachProgramBindsItsOwnNames)
{
    gl::Program both = copy("SSBO_TEST_TARGET"), targetOnly = copy("SSBO_TEST_TARGET", true);
    ASSERT_EQ(both.storage().blocks.size(), 2u);
    EXPECT_EQ(both.storage().blocks[0].name, 1000u);
    EXPECT_EQ(both.storage().blocks[0].slot, 0u);
    EXPECT_EQ(both.storage().blocks[1].name, 1001u);
    EXPECT_EQ(both.storage().blocks[1].slot, 1u);
    ASSERT_EQ(targetOnly.storage().blocks.size(), 1u);
    EXPECT_EQ(targetOnly.storage().blocks[0].name, 1001u);
    EXPECT_EQ(targetOnly.storage().blocks[0].slot, 0u); // 1000's point in `both`

    const std::uint32_t n = 100;
    std::vector<std::uint32_t> values(n);
    for (std::uint32_t i = 0; i < n; ++i) values[i] = i + 1;
    gl::Buffer source = gl::Buffer::fromVector("test.storage.source", values);
    gl::Buffer target("test.storage.target", n * 4);
    source.bindBase(GL_SHADER_STORAGE_BUFFER, 1000);
    target.bindBase(GL_SHADER_STORAGE_BUFFER, 1001);
    run(targetOnly, n, 5); // writes the target at its point 0
    run(both, n, 3);       // reads the source at its point 0
    std::vector<std::uint32_t> out = target.download<std::uint32_t>();
    for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(out[i], 3 * (i + 1)) << i;
    EXPECT_EQ(source.download<std::uint32_t>(), values) << "the source was written";

    // A name bound while its program is in use reaches it at once.
    gl::Buffer other("test.storage.other", n * 4);
    targetOnly.use();
    other.bindBase(GL_SHADER_STORAGE_BUFFER, 1001);
    const std::uint32_t count = n, factor = 7;
    targetOnly.set("count", count);
    targetOnly.set("factor", factor);
    glDispatchCompute(2, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    EXPECT_EQ(other.download<std::uint32_t>(), std::vector<std::uint32_t>(n, 7u));
}

TEST_F(StorageBindingsTest, TwoBlocksUnderOneNameFailToLink)
{
    EXPECT_THROW(copy("SSBO_TEST_SOURCE"), gl::ShaderError);
}

// A name nothing bound reads no buffer at all, never one another name left at the program's point.
TEST_F(StorageBindingsTest, ANameNothingBoundIsSaidAndBindsNothing)
{
    gl::Program p = copy("SSBO_TEST_UNBOUND", true);
    EXPECT_EQ(gl::unboundStorage(p.storage()), "Target (storage name 1002)");
    gl::Buffer elsewhere("test.storage.elsewhere", 64);
    elsewhere.bindBase(GL_SHADER_STORAGE_BUFFER, 1001);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, elsewhere.id()); // left at p's point 0 by someone else
    p.use();
    GLint bound = -1;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 0, &bound);
    EXPECT_EQ(bound, 0);
    // A deleted buffer is bound under no name.
    {
        gl::Buffer gone("test.storage.gone", 64);
        gone.bindBase(GL_SHADER_STORAGE_BUFFER, 1002);
        EXPECT_EQ(gl::unboundStorage(p.storage()), "");
    }
    EXPECT_EQ(gl::unboundStorage(p.storage()), "Target (storage name 1002)");
}

} // namespace
} // namespace bounce
