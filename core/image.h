// Images of linear radiance: float RGB, row 0 at the top. EXR is the data format, PNG only for looking
// at (tone mapped, sRGB). Every writer goes through a temporary name and a rename, so an interrupted
// run never leaves a truncated file behind.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::core {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgb; // width * height * 3, row-major, row 0 at the top

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3, 0.0f) {}
    glm::vec3 at(int x, int y) const
    {
        const float* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, const glm::vec3& v)
    {
        float* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
        p[0] = v.x; p[1] = v.y; p[2] = v.z;
    }
};

// Thrown for a file that cannot be read or written; the message names the file and the problem.
struct ImageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

Image readImage(const std::string& path);                         // .exr (float/half RGB(A)) or .pfm
void writeExr(const std::string& path, const Image& image);       // 32-bit float RGB, atomic
// Tone map (radiance x 2^exposureStops, clamped, sRGB-encoded) and write an 8-bit PNG, atomically.
void writePng(const std::string& path, const Image& image, float exposureStops = 0.0f);
// Writes by extension: .exr, .png (tone mapped), .pfm. Throws ImageError for any other.
void writeImage(const std::string& path, const Image& image, float exposureStops = 0.0f);

// Writes bytes to path through path + ".tmp-<pid>" and a rename; throws ImageError on failure.
void writeFileAtomic(const std::string& path, const std::string& bytes);

} // namespace bounce::core
