// Writes the canonical Cornell box variants as glTF (assets/<name>.gltf + .bin) from core::makeCornell,
// so that other renderers can load exactly the scene the project measures on.
// Usage: bounce_make_assets [output folder]   (default: the source tree's assets/)
#include <cstdio>
#include <exception>
#include <string>

#include "core/cornell.h"
#include "core/gltf_io.h"

int main(int argc, char** argv)
{
    const std::string folder = argc > 1 ? argv[1] : std::string(BOUNCE_SOURCE_ROOT) + "/assets";
    try {
        for (const char* name : {"cornell-area", "cornell-spot", "cornell-point"}) {
            const std::string path = folder + "/" + name + ".gltf";
            bounce::core::writeGltf(bounce::core::makeCornell(name), path);
            std::printf("wrote %s\n", path.c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bounce_make_assets: %s\n", e.what());
        return 1;
    }
    return 0;
}
