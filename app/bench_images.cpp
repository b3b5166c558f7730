#include "app/bench_images.h"

#include <glm/gtc/packing.hpp>

namespace bounce::app {

std::string base64(const std::string& data)
{
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((data.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < data.size(); i += 3) {
        const unsigned v = (unsigned char)data[i] << 16 | (unsigned char)data[i + 1] << 8 | (unsigned char)data[i + 2];
        out += kAlphabet[v >> 18 & 63];
        out += kAlphabet[v >> 12 & 63];
        out += kAlphabet[v >> 6 & 63];
        out += kAlphabet[v & 63];
    }
    if (i + 1 == data.size()) {
        const unsigned v = (unsigned char)data[i] << 16;
        out += kAlphabet[v >> 18 & 63];
        out += kAlphabet[v >> 12 & 63];
        out += "==";
    } else if (i + 2 == data.size()) {
        const unsigned v = (unsigned char)data[i] << 16 | (unsigned char)data[i + 1] << 8;
        out += kAlphabet[v >> 18 & 63];
        out += kAlphabet[v >> 12 & 63];
        out += kAlphabet[v >> 6 & 63];
        out += '=';
    }
    return out;
}

std::string imageScript(const std::string& id, const core::Image& image)
{
    std::string halves;
    halves.reserve(image.rgb.size() * 2);
    for (float v : image.rgb) {
        const std::uint16_t h = glm::packHalf1x16(v);
        halves += char(h & 0xff);
        halves += char(h >> 8);
    }
    return "bounceImage(\"" + id + "\", " + std::to_string(image.width) + ", " + std::to_string(image.height) + ", \"" +
           base64(halves) + "\");\n";
}

std::string writeReportImage(const std::filesystem::path& dir, const std::string& stem, const core::Image& image)
{
    std::string safe = stem;
    for (char& c : safe)
        if (!std::isalnum((unsigned char)c) && c != '.' && c != '_' && c != '-') c = '_';
    const std::string id = "images/" + safe;
    std::filesystem::create_directories(dir / "images");
    const std::string base = (dir / id).string();
    core::writeExr(base + ".exr", image);
    core::writePng(base + ".png", image);
    core::writeFileAtomic(base + ".js", imageScript(id, image));
    return id;
}

} // namespace bounce::app
