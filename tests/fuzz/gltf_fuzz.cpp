// libFuzzer target for the glTF/GLB loader (core/gltf_io.h): any byte string, as a .gltf or a .glb, must
// load or be refused with SceneError; a crash, a sanitizer report, a leak or any other exception is a
// finding. scripts/fuzz.sh builds it with clang (-fsanitize=fuzzer,address,undefined) and runs it;
// replay_main.cpp runs the same function over the seed corpus in the ordinary build.
//
// The loader has no in-memory entry point (it reads a path, through the folder jail of core/gltf_files.h),
// so each input is written to a file in a private temporary folder: the jail then lets a fuzzed URI read
// only that folder, which holds nothing but the input itself.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include <unistd.h>

#include "core/gltf_io.h"

namespace {

namespace fs = std::filesystem;

// One folder per process (libFuzzer's -jobs and -fork run several), removed at exit. The path is never
// destroyed: a handler that atexit() takes while a function-local static is being built runs after that
// static's destructor, and a destroyed path would leave the folder behind.
const fs::path& scratchFolder()
{
    static const fs::path* const folder = [] {
        std::string pattern = (fs::temp_directory_path() / "bounce-gltf-fuzz-XXXXXX").string();
        if (!::mkdtemp(pattern.data())) {
            std::perror("gltf_fuzz: mkdtemp");
            std::abort();
        }
        std::atexit([] {
            std::error_code ec;
            fs::remove_all(scratchFolder(), ec);
        });
        return new fs::path(pattern);
    }();
    return *folder;
}

void writeInput(const fs::path& path, const std::uint8_t* data, std::size_t size)
{
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
        std::perror("gltf_fuzz: writing the input");
        std::abort();
    }
}

// Under libFuzzer the loader's output is silenced; replay_main.cpp keeps it, and says what became of each input.
bool quiet = false;

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    // The loader warns on std::cerr (skipped primitives, textures without source); millions of inputs
    // would drown libFuzzer's own output.
    quiet = !std::getenv("BOUNCE_FUZZ_VERBOSE");
    if (quiet) std::cerr.setstate(std::ios::badbit);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    // Always .gltf: the loader takes bytes starting with "glTF" for a GLB whatever the name, so both framings
    // are fuzzed (a .glb name would only add the refusal of JSON under that name).
    const fs::path path = scratchFolder() / "input.gltf";
    writeInput(path, data, size);
    try {
        const bounce::core::Scene scene = bounce::core::loadGltf(path.string());
        if (!quiet) std::cerr << "loaded: " << scene.meshes.size() << " meshes, " << scene.lights.size() << " lights\n";
    } catch (const bounce::core::SceneError& e) {
        // Refused: what malformed input must get.
        if (!quiet) std::cerr << "refused: " << e.what() << "\n";
    }
    std::error_code ec;
    fs::remove(path, ec);
    return 0;
}
