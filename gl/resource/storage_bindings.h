// Storage blocks bound by name, per program (as Falcor binds a pass's resources by the names its shader
// reflects). A shader declares a storage block with `layout(std430, binding = SSBO_X) buffer Block`, where
// SSBO_X is a name from a bindings.glsl: a number that says which buffer the block reads, never a GL binding
// point, so names are free to exceed any driver's limit and no two meanings need share one. The program
// strips the names from the source it compiles (takeStorageNames), and after linking gives its active
// blocks its own binding points 0..k-1 (assignStorageSlots). C++ binds a buffer under a name
// (Buffer::bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_X) records it in the context's table); the program in use
// binds the buffers of its own names to its own points, when it is put in use (Program::use) and whenever a
// buffer of one of its names is bound while it is in use. So what a program reads under a name is what was
// last bound under that name, as when names were binding points, and nothing a program does not name can
// take one of its points.
#pragma once

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace bounce::gl {

// The most storage blocks one program may use: three below the smallest per-stage limit of the drivers
// Bounce runs on (llvmpipe's 16 GL_MAX_*_SHADER_STORAGE_BLOCKS), so that a pass can grow a little before it
// meets a limit. tests/gl/conformance_test.cpp holds every program a technique links to it.
constexpr int kMaxStorageBlocksPerProgram = 13;

// One active storage block of a linked program.
struct StorageBlock {
    std::string block; // its name in GLSL (the block's, not the instance's)
    unsigned name = 0; // what it is bound by (SSBO_*)
    unsigned slot = 0; // the program's binding point for it
};

// The active storage blocks of one program, by slot.
struct StorageLayout {
    std::string label; // the program's
    std::vector<StorageBlock> blocks;
};

// Block name -> storage name, gathered from the stages of one program.
using StorageNames = std::map<std::string, unsigned>;

// Strips `binding = NAME` from every storage block's layout in a preprocessed stage (`source`, its path
// under glsl/ for messages) and records the block's name in `names`. NAME is an SSBO_* macro defined in the
// source as a number (or as another such macro), or a literal number (the tests' own shaders). Throws
// ShaderError for a block with no binding, a name with no number, or one block with two names.
std::string takeStorageNames(const std::string& source, const std::string& path, StorageNames& names);

// Gives the active storage blocks of a linked program the binding points 0..k-1, in the order of their
// names (glShaderStorageBlockBinding). Throws ShaderError when an active block has no name, or two share one.
std::shared_ptr<const StorageLayout> assignStorageSlots(unsigned program, const std::string& label,
                                                        const StorageNames& names);

// Every program linked since the process began (or since the last reset), with its blocks: what the
// conformance test reports and bounds. Labels repeat where a program is linked again.
const std::vector<std::shared_ptr<const StorageLayout>>& linkedStorageLayouts();
void resetLinkedStorageLayouts();

// Records `buffer` (a GL buffer name) under storage name `name`, and binds it at once where the program in
// use reads that name.
void bindStorage(unsigned name, unsigned buffer);
// A deleted buffer is bound under no name (GL unbinds it from every point of the current context).
void forgetStorageBuffer(unsigned buffer);
// Puts `layout`'s program in use for storage: binds every buffer of its names to its points (nothing where
// no buffer was bound under a name, so that it never reads another name's buffer).
void useStorage(std::shared_ptr<const StorageLayout> layout);
// The blocks of `layout` under whose names no buffer is bound, as "Block (storage name N), ..."; empty when
// there are none. dispatchCompute (gl/resource/dispatch.h) refuses such a dispatch: a std430 block is
// active wherever it is declared, so a pass declares only the blocks it reads, and each is bound before it
// runs.
std::string unboundStorage(const StorageLayout& layout);

} // namespace bounce::gl
