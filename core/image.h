// Images of linear radiance: float RGB, row 0 at the top. EXR is the data format, PNG only for looking
// at (tone mapped, sRGB). Every writer goes through a temporary name and a rename, so an interrupted
// run never leaves a truncated file behind.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
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
        p[0] = v.x;
        p[1] = v.y;
        p[2] = v.z;
    }
};

// Thrown for a file that cannot be read or written; the message names the file and the problem.
struct ImageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

Image readImage(const std::string& path); // .exr (float/half RGB(A)) or .pfm
// Decodes bytes as readImage would decode them from a file named path (by extension); path names errors.
Image decodeImage(const std::string& path, const std::string& bytes);
void writeExr(const std::string& path, const Image& image); // 32-bit float RGB, atomic
// Tone map (radiance x 2^exposureStops, clamped, sRGB-encoded) and write an 8-bit PNG, atomically.
void writePng(const std::string& path, const Image& image, float exposureStops = 0.0f);
// Writes by extension: .exr, .png (tone mapped), .pfm. Throws ImageError for any other.
void writeImage(const std::string& path, const Image& image, float exposureStops = 0.0f);

// The bytes writeImage would write (by extension: .exr, .png tone mapped, .pfm).
std::string encodeImage(const std::string& path, const Image& image, float exposureStops = 0.0f);

// Writes bytes to path through path + ".tmp-<pid>" and a rename; throws ImageError on failure.
void writeFileAtomic(const std::string& path, const std::string& bytes);

// Checks, before any work, that path can be written: not a folder, its folder exists or is created, a
// file can be created there. Throws ImageError saying why not.
void checkOutputPath(const std::string& path);

// Files that appear together or not at all (a run's EXR, PNG and JSON): commit() writes every file to a
// temporary name beside it, then renames them all into place. When a write or a rename fails, every
// temporary and every file of the set already renamed are removed, and ImageError names the file.
class FileSet {
public:
    void add(const std::string& path, std::string bytes);
    void addImage(const std::string& path, const Image& image, float exposureStops = 0.0f);
    void commit();

private:
    std::vector<std::pair<std::string, std::string>> files_;
};

} // namespace bounce::core
