// GLSL programs loaded from glsl/ with #include "path" (resolved against the glsl/ root, expanded where
// it stands; each file's own #ifndef guard keeps it to one copy) and #defines injected
// after #version. Uniforms are set by name with glProgramUniform*.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/resource/handle.h"
#include "gl/resource/storage_bindings.h"

namespace bounce::gl {

struct ProgramDeleter {
    void operator()(unsigned id) const;
};

// Thrown when a shader cannot be read, compiled or linked; the message names the file and line.
struct ShaderError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Define {
    std::string name;
    std::string value;
};

// The folder holding the shaders: $BOUNCE_ROOT/glsl, else the source tree's glsl/.
std::string glslRoot();
// Reads a shader with its #includes expanded and defines injected (exposed for tests).
std::string preprocessShader(const std::string& relativePath, const std::vector<Define>& defines);

// Called with every shader stage's source as it goes to the driver (its path under glsl/ and the GL stage
// enum), for checks by another compiler (tests/gl/conformance_test.cpp: the Khronos reference compiler);
// an empty function: none. One observer for the process, used from the GL thread.
using ShaderSourceObserver = std::function<void(const std::string& path, unsigned stage, const std::string& source)>;
void setShaderSourceObserver(ShaderSourceObserver observer);

class Program {
public:
    Program() = default;
    static Program graphics(const std::string& label, const std::string& vertexPath, const std::string& fragmentPath,
                            const std::vector<Define>& defines = {}, const std::string& geometryPath = {});
    static Program compute(const std::string& label, const std::string& path, const std::vector<Define>& defines = {});

    unsigned id() const { return handle_.id(); }
    explicit operator bool() const { return bool(handle_); }
    // glUseProgram, and the buffers bound under the program's storage names bound to its binding points
    // (gl/resource/storage_bindings.h).
    void use() const;
    // The program's active storage blocks: their names and binding points.
    const StorageLayout& storage() const;

    // Setting a uniform the program does not have (optimised away) is silently ignored.
    void set(const std::string& name, int v);
    void set(const std::string& name, unsigned v);
    void set(const std::string& name, float v);
    void set(const std::string& name, const glm::vec2& v);
    void set(const std::string& name, const glm::vec3& v);
    void set(const std::string& name, const glm::vec4& v);
    void set(const std::string& name, const glm::ivec2& v);
    void set(const std::string& name, const glm::ivec3& v);
    void set(const std::string& name, const glm::mat3& v);
    void set(const std::string& name, const glm::mat4& v);

private:
    int location(const std::string& name);
    Handle<ProgramDeleter> handle_;
    std::shared_ptr<const StorageLayout> storage_;
    std::map<std::string, int> locations_;
};

} // namespace bounce::gl
