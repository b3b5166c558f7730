// Helpers shared by the core I/O tests: a fresh scratch folder per test, the repository root, files.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace bounce::core::test {

namespace fs = std::filesystem;

// An empty folder under the build tree's test-out/, named after the running test.
inline fs::path scratchDir()
{
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir =
        fs::path(BOUNCE_TEST_OUT) / "core" / (std::string(info->test_suite_name()) + "." + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Where assets/, package.json and node_modules/ are: BOUNCE_ROOT (set by ctest) or the configured source.
inline fs::path repoRoot()
{
    if (const char* root = std::getenv("BOUNCE_ROOT"); root && *root) return root;
    return BOUNCE_SOURCE_ROOT;
}

inline void writeFile(const fs::path& path, const std::string& bytes)
{
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

inline std::string readFile(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace bounce::core::test
