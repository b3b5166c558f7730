#include "core/image.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <stb_image_write.h> // implementation in Debian's libstb
#include <tinyexr.h>         // implementation in Debian's libtinyexr

namespace bounce::core {

namespace {

// Larger images are refused before allocating: no image of the project comes near 16k x 16k.
constexpr std::uint64_t kMaxPixels = std::uint64_t(1) << 28;

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
    throw ImageError(path + ": " + problem);
}

std::string lowerExtension(const std::string& path)
{
    const std::size_t slash = path.find_last_of('/');
    const std::size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

std::string readWholeFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, std::string("cannot open for reading: ") + std::strerror(errno));
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (in.bad()) fail(path, "read error");
    return bytes.str();
}

void checkWritable(const std::string& path, const Image& image)
{
    if (image.width <= 0 || image.height <= 0) fail(path, "cannot write an empty image");
    if (image.rgb.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
        fail(path, "pixel buffer size does not match " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " RGB");
}

Image decodeExr(const std::string& path, const std::string& bytes)
{
    float* rgba = nullptr;
    int width = 0, height = 0;
    const char* err = nullptr;
    // LoadEXRFromMemory converts half and float channels alike to float RGBA (alpha 1 when absent).
    const int rc = LoadEXRFromMemory(&rgba, &width, &height, reinterpret_cast<const unsigned char*>(bytes.data()),
                                     bytes.size(), &err);
    if (rc != TINYEXR_SUCCESS) {
        const std::string why = err ? err : "unknown error";
        if (err) FreeEXRErrorMessage(err);
        std::free(rgba);
        fail(path, "not a readable EXR (" + why + ")");
    }
    if (width <= 0 || height <= 0 || std::uint64_t(width) * std::uint64_t(height) > kMaxPixels) {
        std::free(rgba);
        fail(path, "EXR has unusable size " + std::to_string(width) + "x" + std::to_string(height));
    }
    Image image(width, height);
    const std::size_t n = std::size_t(width) * std::size_t(height);
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) image.rgb[i * 3 + c] = rgba[i * 4 + c];
    std::free(rgba);
    return image;
}

// PFM (Portable Float Map): "PF" (RGB) or "Pf" (grey), width height, scale (negative: little-endian),
// then rows from the bottom up.
Image decodePfm(const std::string& path, const std::string& bytes)
{
    std::istringstream header(bytes);
    std::string magic;
    long long width = 0, height = 0;
    double scale = 0.0;
    header >> magic >> width >> height >> scale;
    if (!header || (magic != "PF" && magic != "Pf")) fail(path, "not a PFM file (bad header)");
    if (width <= 0 || height <= 0 || std::uint64_t(width) * std::uint64_t(height) > kMaxPixels)
        fail(path, "PFM has unusable size " + std::to_string(width) + "x" + std::to_string(height));
    if (scale == 0.0 || !std::isfinite(scale)) fail(path, "PFM scale must be finite and non-zero");
    // Exactly one whitespace character separates the header from the data.
    const std::streamoff headerEnd = header.tellg();
    if (headerEnd < 0) fail(path, "PFM is truncated: no pixel data");
    const std::size_t dataStart = std::size_t(headerEnd) + 1;
    const int channels = magic == "PF" ? 3 : 1;
    const std::size_t n = std::size_t(width) * std::size_t(height) * std::size_t(channels);
    if (bytes.size() < dataStart || bytes.size() - dataStart < n * 4)
        fail(path, "PFM is truncated: expected " + std::to_string(n * 4) + " bytes of pixels");
    const bool bigEndian = scale > 0.0;
    Image image{int(width), int(height)};
    for (std::size_t i = 0; i < n; ++i) {
        unsigned char b[4];
        std::memcpy(b, bytes.data() + dataStart + i * 4, 4);
        if (bigEndian) {
            std::swap(b[0], b[3]);
            std::swap(b[1], b[2]);
        }
        float v;
        std::memcpy(&v, b, 4);
        const std::size_t pixel = i / std::size_t(channels);
        const std::size_t x = pixel % std::size_t(width);
        const std::size_t yFromBottom = pixel / std::size_t(width);
        const std::size_t row = std::size_t(height) - 1 - yFromBottom;
        float* dst = &image.rgb[(row * std::size_t(width) + x) * 3];
        if (channels == 3)
            dst[i % 3] = v;
        else
            dst[0] = dst[1] = dst[2] = v;
    }
    return image;
}

std::string encodePfm(const std::string& path, const Image& image)
{
    checkWritable(path, image);
    // Scale -1: little-endian floats, which is what this machine stores.
    std::string bytes = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
    const std::size_t rowBytes = std::size_t(image.width) * 3 * sizeof(float);
    const std::size_t headerSize = bytes.size();
    bytes.resize(headerSize + rowBytes * std::size_t(image.height));
    for (int y = 0; y < image.height; ++y) {
        const float* src = &image.rgb[std::size_t(image.height - 1 - y) * std::size_t(image.width) * 3];
        std::memcpy(bytes.data() + headerSize + std::size_t(y) * rowBytes, src, rowBytes);
    }
    return bytes;
}

std::uint8_t encodeSrgb8(float linear)
{
    if (!(linear > 0.0f)) return 0; // also maps NaN to black
    if (linear >= 1.0f) return 255;
    const float encoded = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return std::uint8_t(std::lround(std::clamp(encoded, 0.0f, 1.0f) * 255.0f));
}

void appendToString(void* context, void* data, int size)
{
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}

} // namespace

Image decodeImage(const std::string& path, const std::string& bytes)
{
    const std::string ext = lowerExtension(path);
    if (ext == ".exr") return decodeExr(path, bytes);
    if (ext == ".pfm") return decodePfm(path, bytes);
    fail(path, "unknown image extension '" + ext + "' (readable: .exr, .pfm)");
}

Image readImage(const std::string& path)
{
    const std::string ext = lowerExtension(path);
    if (ext != ".exr" && ext != ".pfm") fail(path, "unknown image extension '" + ext + "' (readable: .exr, .pfm)");
    return decodeImage(path, readWholeFile(path));
}

std::string encodeExr(const std::string& path, const Image& image)
{
    checkWritable(path, image);
    const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
    // EXR readers expect channels in alphabetical order: B, G, R.
    std::vector<float> planes[3];
    for (int c = 0; c < 3; ++c) {
        planes[c].resize(n);
        for (std::size_t i = 0; i < n; ++i) planes[c][i] = image.rgb[i * 3 + std::size_t(2 - c)];
    }
    unsigned char* planePointers[3] = {reinterpret_cast<unsigned char*>(planes[0].data()),
                                       reinterpret_cast<unsigned char*>(planes[1].data()),
                                       reinterpret_cast<unsigned char*>(planes[2].data())};
    EXRImage exrImage;
    InitEXRImage(&exrImage);
    exrImage.images = planePointers;
    exrImage.width = image.width;
    exrImage.height = image.height;
    exrImage.num_channels = 3;

    EXRHeader header;
    InitEXRHeader(&header);
    EXRChannelInfo channels[3] = {};
    int pixelTypes[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
    const char* names[3] = {"B", "G", "R"};
    for (int c = 0; c < 3; ++c) std::strncpy(channels[c].name, names[c], sizeof channels[c].name - 1);
    header.num_channels = 3;
    header.channels = channels;
    header.pixel_types = pixelTypes;
    header.requested_pixel_types = pixelTypes;
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP; // lossless, keeps data files small

    unsigned char* memory = nullptr;
    const char* err = nullptr;
    const std::size_t size = SaveEXRImageToMemory(&exrImage, &header, &memory, &err);
    if (size == 0) {
        const std::string why = err ? err : "unknown error";
        if (err) FreeEXRErrorMessage(err);
        std::free(memory);
        fail(path, "EXR encoding failed (" + why + ")");
    }
    std::string bytes(reinterpret_cast<const char*>(memory), size);
    std::free(memory);
    return bytes;
}

std::string encodePng(const std::string& path, const Image& image, float exposureStops)
{
    checkWritable(path, image);
    const float scale = std::exp2(exposureStops);
    const std::size_t n = std::size_t(image.width) * std::size_t(image.height) * 3;
    std::vector<std::uint8_t> pixels(n);
    for (std::size_t i = 0; i < n; ++i) pixels[i] = encodeSrgb8(image.rgb[i] * scale);
    std::string bytes;
    if (!stbi_write_png_to_func(appendToString, &bytes, image.width, image.height, 3, pixels.data(), image.width * 3))
        fail(path, "PNG encoding failed");
    return bytes;
}

std::string encodeImage(const std::string& path, const Image& image, float exposureStops)
{
    const std::string ext = lowerExtension(path);
    if (ext == ".exr") return encodeExr(path, image);
    if (ext == ".png") return encodePng(path, image, exposureStops);
    if (ext == ".pfm") return encodePfm(path, image);
    fail(path, "unknown image extension '" + ext + "' (writable: .exr, .png, .pfm)");
}

void writeExr(const std::string& path, const Image& image)
{
    writeFileAtomic(path, encodeExr(path, image));
}

void writePng(const std::string& path, const Image& image, float exposureStops)
{
    writeFileAtomic(path, encodePng(path, image, exposureStops));
}

void writeImage(const std::string& path, const Image& image, float exposureStops)
{
    writeFileAtomic(path, encodeImage(path, image, exposureStops));
}

namespace {
// Unique to the process and the thread: concurrent writers of one path (two bench runs filling the same
// reference cache entry, two threads of one) each write their own temporary, and the last rename wins whole.
std::string temporaryName(const std::string& path)
{
    return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(::gettid());
}

// Writes bytes to temporaryName(path); on failure removes it and throws.
void writeTemporary(const std::string& path, const std::string& bytes)
{
    const std::string temp = temporaryName(path);
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) fail(path, "cannot create " + temp + ": " + std::strerror(errno));
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) {
        std::remove(temp.c_str());
        fail(path, "write error (disk full?) on " + temp);
    }
}
} // namespace

void checkOutputPath(const std::string& path)
{
    const std::filesystem::path p(path);
    if (p.filename().empty()) fail(path, "names a folder, not a file");
    std::error_code ec;
    if (std::filesystem::is_directory(p, ec)) fail(path, "is a folder");
    if (p.has_parent_path()) {
        std::filesystem::create_directories(p.parent_path(), ec);
        if (!std::filesystem::is_directory(p.parent_path()))
            fail(path, "its folder " + p.parent_path().string() + " cannot be created" +
                           (ec ? ": " + ec.message() : std::string()));
    }
    writeTemporary(path, {});
    std::remove(temporaryName(path).c_str());
}

void FileSet::add(const std::string& path, std::string bytes)
{
    files_.emplace_back(path, std::move(bytes));
}

void FileSet::addImage(const std::string& path, const Image& image, float exposureStops)
{
    add(path, encodeImage(path, image, exposureStops));
}

void FileSet::commit()
{
    std::size_t written = 0;
    try {
        for (; written < files_.size(); ++written) writeTemporary(files_[written].first, files_[written].second);
    } catch (...) {
        for (std::size_t i = 0; i < written; ++i) std::remove(temporaryName(files_[i].first).c_str());
        throw;
    }
    for (std::size_t i = 0; i < files_.size(); ++i) {
        const std::string& path = files_[i].first;
        if (std::rename(temporaryName(path).c_str(), path.c_str()) != 0) {
            const std::string why = std::strerror(errno);
            for (std::size_t j = i; j < files_.size(); ++j) std::remove(temporaryName(files_[j].first).c_str());
            for (std::size_t j = 0; j < i; ++j) std::remove(files_[j].first.c_str());
            fail(path, "cannot rename its temporary into place: " + why + "; no file of the set was kept");
        }
    }
    files_.clear();
}

void writeFileAtomic(const std::string& path, const std::string& bytes)
{
    writeTemporary(path, bytes);
    const std::string temp = temporaryName(path);
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::remove(temp.c_str());
        fail(path, "cannot rename " + temp + " into place: " + why);
    }
}

} // namespace bounce::core
