// Runs the fuzz target (gltf_fuzz.cpp) once on every file named or found under the folders named, without
// libFuzzer: the seed corpus and any crash a fuzzing run saved are checked by the ordinary (gcc) build and by
// the sanitizer build (scripts/sanitize.sh). An input that crashes, or throws anything but SceneError,
// ends the process with a non-zero status. The loader's warnings stay on stderr here (LLVMFuzzerInitialize,
// which silences them for libFuzzer, is not called).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv)
{
    namespace fs = std::filesystem;
    std::vector<fs::path> inputs;
    for (int i = 1; i < argc; ++i) {
        if (fs::is_directory(argv[i])) {
            for (const fs::directory_entry& e : fs::recursive_directory_iterator(argv[i]))
                if (e.is_regular_file()) inputs.push_back(e.path());
        } else {
            inputs.emplace_back(argv[i]);
        }
    }
    std::sort(inputs.begin(), inputs.end()); // the same order in every run
    if (inputs.empty()) {
        std::cerr << "usage: gltf_fuzz_replay FILE_OR_FOLDER...: no inputs found\n";
        return 2;
    }
    for (const fs::path& p : inputs) {
        std::ifstream in(p, std::ios::binary);
        if (!in) {
            std::cerr << "cannot read " << p << "\n";
            return 2;
        }
        const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::cout << "input " << p.filename().string() << " (" << bytes.size() << " bytes)" << std::endl;
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }
    std::cout << inputs.size() << " inputs loaded or refused, none crashed" << std::endl;
    return 0;
}
