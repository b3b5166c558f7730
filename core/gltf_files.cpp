#include "core/gltf_files.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace bounce::core::gltf {

namespace fs = std::filesystem;

namespace {

// Returns the URI relative to the scene folder when absPath is a candidate tinygltf built from it.
bool relativeToFolder(const FolderJail& jail, const std::string& absPath, std::string* rel)
{
    if (absPath.compare(0, jail.prefix.size(), jail.prefix) != 0) return false;
    *rel = absPath.substr(jail.prefix.size());
    return true;
}

// An absolute URI (joined as "folder//abs") or one with a '..' part: it leaves by its name alone.
bool leavesByName(const std::string& rel)
{
    if (!rel.empty() && rel.front() == '/') return true;
    for (const fs::path& part : fs::path(rel))
        if (part == "..") return true;
    return false;
}

bool staysInFolder(const FolderJail& jail, const std::string& absPath, const std::string& rel)
{
    if (rel.empty() || leavesByName(rel)) return false;
    std::error_code ec;
    const std::string resolved = fs::weakly_canonical(absPath, ec).string(); // follows symbolic links
    return !ec && resolved.compare(0, jail.prefix.size(), jail.prefix) == 0;
}

// "", ".", "./", "dir/.": a URI that names the scene's folder (or one below it) or nothing at all, which is
// no file, whether or not it stays in the folder.
bool namesNoFile(const std::string& rel)
{
    if (rel.empty() || rel.back() == '/') return true;
    const fs::path last = fs::path(rel).filename();
    return last == "." || last.empty();
}

bool jailFileExists(const std::string& absPath, void* user)
{
    auto* jail = static_cast<FolderJail*>(user);
    std::string rel;
    // tinygltf also tries the current directory; that is outside the scene and silently absent.
    if (!relativeToFolder(*jail, absPath, &rel)) return false;
    if (namesNoFile(rel) && !leavesByName(rel)) {
        jail->notFiles.push_back(rel);
        return false;
    }
    if (!staysInFolder(*jail, absPath, rel)) {
        jail->refused.push_back(rel);
        return false;
    }
    std::error_code ec;
    if (fs::is_regular_file(absPath, ec)) return true;
    if (fs::is_directory(absPath, ec))
        jail->notFiles.push_back(rel);
    else
        jail->missing.push_back(rel);
    return false;
}

// No shell-style expansion (~, $VAR): a URI names a file, nothing else.
std::string jailExpandFilePath(const std::string& path, void*)
{
    return path;
}

bool jailReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& absPath, void* user)
{
    auto* jail = static_cast<FolderJail*>(user);
    std::string rel;
    if (!relativeToFolder(*jail, absPath, &rel) || !staysInFolder(*jail, absPath, rel)) {
        if (err) *err += "refused to read outside the scene's folder: " + absPath + "\n";
        return false;
    }
    std::ifstream in(absPath, std::ios::binary);
    if (!in) {
        if (err) *err += "cannot open " + absPath + "\n";
        return false;
    }
    out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return !in.bad();
}

bool jailWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*)
{
    if (err) *err += "writing through tinygltf is not used\n";
    return false;
}

} // namespace

void fail(const std::string& path, const std::string& problem)
{
    throw SceneError(path + ": " + problem);
}

std::string lowerExtension(const std::string& path)
{
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

tinygltf::FsCallbacks jailCallbacks(FolderJail& jail)
{
    return {jailFileExists, jailExpandFilePath, jailReadWholeFile, jailWriteWholeFile, &jail};
}

bool keepEncodedImage(tinygltf::Image* image, const int imageIndex, std::string* err, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user)
{
    const auto* jail = static_cast<const FolderJail*>(user);
    if (image->bufferView >= 0) {
        // tinygltf hands over buffer.data + byteOffset unchecked; check before touching a byte.
        const tinygltf::Model& model = *jail->model;
        const auto& view = model.bufferViews[std::size_t(image->bufferView)];
        const std::uint64_t bufferSize = model.buffers[std::size_t(view.buffer)].data.size();
        if (view.byteOffset > bufferSize || view.byteLength > bufferSize - view.byteOffset) {
            if (err)
                *err += "image " + std::to_string(imageIndex) + ": bufferView " + std::to_string(image->bufferView) +
                        " extends beyond the end of buffer " + std::to_string(view.buffer) + "\n";
            return false;
        }
    }
    if (size < 0) return false;
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

} // namespace bounce::core::gltf
