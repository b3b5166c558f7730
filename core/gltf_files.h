// The file side of glTF I/O, internal to core/gltf_read.cpp and core/gltf_write.cpp (the public API is
// core/gltf_io.h): errors that name the file, and the folder jail through which tinygltf sees the file
// system when loading, so that a scene can read only files in its own folder or below it.
#pragma once

#include <string>
#include <vector>

#include <tiny_gltf.h> // implementation in Debian's libtinygltf: the header only declares

#include "core/gltf_io.h"

namespace bounce::core::gltf {

// Throws SceneError("path: problem").
[[noreturn]] void fail(const std::string& path, const std::string& problem);

// ".gltf", ".glb"...: the extension in lower case.
std::string lowerExtension(const std::string& path);

// The file system as tinygltf sees it: only files inside the scene's folder exist. The refusal happens
// in FileExists, before anything is read, and is recorded so that the error names the offending URI.
struct FolderJail {
    std::string prefix; // canonical scene folder, with a trailing '/'
    std::vector<std::string> refused;
    std::vector<std::string> missing;
    std::vector<std::string> notFiles; // "", ".", "dir/": URIs that name the folder or nothing, not a file
    tinygltf::Model* model = nullptr;  // being filled; the image callback checks buffer views against it
};

// tinygltf's file callbacks confined to the jail: URIs that leave the folder (absolute, '..', or a
// symbolic link out of it) do not exist; no shell expansion; no writing.
tinygltf::FsCallbacks jailCallbacks(FolderJail& jail);

// tinygltf's image loader (user data: the FolderJail): keeps images encoded, after checking an embedded
// image's buffer view against its buffer; only the images a material uses as base colour are decoded,
// later, with limits.
bool keepEncodedImage(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn, int reqWidth,
                      int reqHeight, const unsigned char* bytes, int size, void* user);

} // namespace bounce::core::gltf
