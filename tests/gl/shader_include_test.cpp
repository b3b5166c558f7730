// The shader #include expander. A file included first inside a dropped #ifdef and then unconditionally
// must still reach the compiler (the microrender gather shader, without RAY_CAST, lost the scene's
// structs that way); an include cycle is refused with the file named.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "gl/resource/program.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

// Points BOUNCE_ROOT at a scratch tree with a glsl/ folder for the test's life. Each test has its own tree:
// ctest runs the tests of this suite in parallel, and a shared one was removed under a running test.
class ShaderIncludeTest : public GlTest {
protected:
    void SetUp() override
    {
        GlTest::SetUp();
        root_ = fs::path(BOUNCE_TEST_OUT) / "shader-include" /
                ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(root_);
        fs::create_directories(root_ / "glsl");
        if (const char* old = std::getenv("BOUNCE_ROOT")) old_ = old, hadOld_ = true;
        setenv("BOUNCE_ROOT", root_.c_str(), 1);
    }
    void TearDown() override
    {
        if (hadOld_)
            setenv("BOUNCE_ROOT", old_.c_str(), 1);
        else
            unsetenv("BOUNCE_ROOT");
        GlTest::TearDown();
    }
    void write(const std::string& name, const std::string& text) { std::ofstream(root_ / "glsl" / name) << text; }

    static int count(const std::string& text, const std::string& what)
    {
        int n = 0;
        for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
        return n;
    }

    fs::path root_;
    std::string old_;
    bool hadOld_ = false;
};

const char* kGuarded = "#ifndef SHARED_GLSL\n#define SHARED_GLSL\nstruct Shared { float v; };\n#endif\n";

TEST_F(ShaderIncludeTest, IncludeFirstSeenInADroppedBranchStillReachesTheCompiler)
{
    write("shared.glsl", kGuarded);
    write("optional.glsl", "#include \"shared.glsl\"\nfloat optionalValue() { return 1.0; }\n");
    write("top.comp", "#version 450 core\n"
                      "layout(local_size_x = 1) in;\n"
                      "#ifdef WITH_OPTIONAL\n#include \"optional.glsl\"\n#endif\n"
                      "#include \"shared.glsl\"\n"
                      "layout(std430, binding = 0) buffer Out { float result; };\n"
                      "void main() { Shared s; s.v = 2.0; result = s.v; }\n");
    const std::string src = gl::preprocessShader("top.comp", {});
    EXPECT_EQ(count(src, "struct Shared"), 2) << src; // once in the dropped branch, once for real
    EXPECT_NO_THROW(gl::Program::compute("test.include", "top.comp"));
    EXPECT_NO_THROW(gl::Program::compute("test.include", "top.comp", {{"WITH_OPTIONAL", "1"}}));
}

TEST_F(ShaderIncludeTest, IncludeCycleIsRefusedNamingTheFile)
{
    write("a.glsl", "#include \"b.glsl\"\n");
    write("b.glsl", "#include \"a.glsl\"\n");
    write("top.comp", "#version 450 core\n#include \"a.glsl\"\nvoid main() {}\n");
    try {
        gl::preprocessShader("top.comp", {});
        FAIL() << "expected a ShaderError";
    } catch (const gl::ShaderError& e) {
        EXPECT_NE(std::string(e.what()).find("a.glsl"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace bounce
