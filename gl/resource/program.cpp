#include "gl/resource/program.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <glm/gtc/type_ptr.hpp>

#include "gl/context/context.h"
#include "gl/debug.h"
#include "gl/gl.h"

namespace bounce::gl {

void ProgramDeleter::operator()(unsigned id) const
{
    glDeleteProgram(id);
}

std::string glslRoot()
{
    if (const char* root = std::getenv("BOUNCE_ROOT"); root && *root) return std::string(root) + "/glsl";
    return std::string(BOUNCE_SOURCE_ROOT) + "/glsl";
}

namespace {

std::string readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ShaderError("cannot read shader '" + path + "'");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Expands #include "x" recursively, wherever it appears: every shared file has its own #ifndef guard, so a
// repeat expands to nothing. Expanding a file only once instead is wrong when its first #include sits in a
// branch the preprocessor drops (#ifdef RAY_CAST ... #include "common/raycast.glsl"), which would take the
// file's text out of every later, unconditional include too. Source-string numbers in #line directives
// index `files` (one entry per file), so a compile error can be mapped back to its file; an include
// cycle is an error.
void expand(const std::string& rel, std::vector<std::string>& files, std::vector<std::string>& stack,
            std::ostringstream& out, bool top)
{
    for (const std::string& open : stack)
        if (open == rel) throw ShaderError(stack.back() + ": #include cycle through '" + rel + "'");
    int index = 0;
    while (index < int(files.size()) && files[std::size_t(index)] != rel) ++index;
    if (index == int(files.size())) files.push_back(rel);
    stack.push_back(rel);
    std::istringstream in(readFile(glslRoot() + "/" + rel));
    std::string line;
    int n = 0;
    if (!top) out << "#line 1 " << index << "\n";
    while (std::getline(in, line)) {
        ++n;
        const auto p = line.find_first_not_of(" \t");
        if (p != std::string::npos && line.compare(p, 8, "#include") == 0) {
            const auto a = line.find('"'), b = line.rfind('"');
            if (a == std::string::npos || b <= a)
                throw ShaderError(rel + ":" + std::to_string(n) + ": malformed #include");
            expand(line.substr(a + 1, b - a - 1), files, stack, out, false);
            out << "#line " << n + 1 << " " << index << "\n";
            continue;
        }
        out << line << "\n";
        if (top && p != std::string::npos && line.compare(p, 8, "#version") == 0)
            out << "@DEFINES@\n#line " << n + 1 << " 0\n";
    }
    stack.pop_back();
}

std::string preprocess(const std::string& rel, const std::vector<Define>& defines, std::vector<std::string>& files)
{
    std::vector<std::string> stack;
    std::ostringstream out;
    expand(rel, files, stack, out, true);
    std::string src = out.str();
    std::string defs;
    for (const Define& d : defines) defs += "#define " + d.name + " " + d.value + "\n";
    const auto at = src.find("@DEFINES@\n");
    if (at == std::string::npos) throw ShaderError(rel + ": no #version line");
    src.replace(at, 10, defs);
    return src;
}

// Rewrites "0(12)" / "0:12" style source numbers in a driver's log into file names where possible.
std::string annotateLog(const std::string& log, const std::vector<std::string>& files)
{
    std::ostringstream out;
    out << log;
    out << "(source-string numbers:";
    for (std::size_t i = 0; i < files.size(); ++i) out << " " << i << "=" << files[i];
    out << ")";
    return out.str();
}

// What every shader may specialise on about the driver at hand: BOUNCE_IEEE_DIVISION where a / b is
// rounded to nearest as IEEE 754 says (llvmpipe: LLVM's fdiv; GLSL allows 2.5 ulp and NVIDIA's is not),
// so that glsl/common/raycast.glsl's rayDivide need not correct it.
std::vector<Define> withDriverDefines(std::vector<Define> defines)
{
    if (softwareRasterizer()) defines.push_back({"BOUNCE_IEEE_DIVISION", "1"});
    return defines;
}

ShaderSourceObserver& sourceObserver()
{
    static ShaderSourceObserver observer;
    return observer;
}

unsigned compileStage(unsigned stage, const std::string& rel, const std::vector<Define>& defines,
                      StorageNames& storageNames)
{
    std::vector<std::string> files;
    const std::string src = takeStorageNames(preprocess(rel, withDriverDefines(defines), files), rel, storageNames);
    if (sourceObserver()) sourceObserver()(rel, stage, src);
    const unsigned s = glCreateShader(stage);
    const char* p = src.c_str();
    glShaderSource(s, 1, &p, nullptr);
    glCompileShader(s);
    int ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        int len = 0;
        glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
        std::string log(std::size_t(len > 0 ? len : 1), '\0');
        glGetShaderInfoLog(s, len, nullptr, log.data());
        glDeleteShader(s);
        throw ShaderError("compiling " + rel + ":\n" + annotateLog(log, files));
    }
    return s;
}

unsigned link(const std::string& label, const std::vector<unsigned>& stages)
{
    const unsigned prog = glCreateProgram();
    for (unsigned s : stages) glAttachShader(prog, s);
    glLinkProgram(prog);
    for (unsigned s : stages) {
        glDetachShader(prog, s);
        glDeleteShader(s);
    }
    int ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        int len = 0;
        glGetProgramiv(prog, GL_INFO_LOG_LENGTH, &len);
        std::string log(std::size_t(len > 0 ? len : 1), '\0');
        glGetProgramInfoLog(prog, len, nullptr, log.data());
        glDeleteProgram(prog);
        throw ShaderError("linking program '" + label + "':\n" + log);
    }
    labelObject(GL_PROGRAM, prog, label);
    return prog;
}

} // namespace

void setShaderSourceObserver(ShaderSourceObserver observer)
{
    sourceObserver() = std::move(observer);
}

std::string preprocessShader(const std::string& rel, const std::vector<Define>& defines)
{
    std::vector<std::string> files;
    return preprocess(rel, defines, files);
}

Program Program::graphics(const std::string& label, const std::string& vs, const std::string& fs,
                          const std::vector<Define>& defines, const std::string& gs)
{
    StorageNames names;
    std::vector<unsigned> stages{compileStage(GL_VERTEX_SHADER, vs, defines, names)};
    if (!gs.empty()) stages.push_back(compileStage(GL_GEOMETRY_SHADER, gs, defines, names));
    stages.push_back(compileStage(GL_FRAGMENT_SHADER, fs, defines, names));
    Program p;
    p.handle_ = Handle<ProgramDeleter>(link(label, stages));
    p.storage_ = assignStorageSlots(p.id(), label, names);
    return p;
}

Program Program::compute(const std::string& label, const std::string& path, const std::vector<Define>& defines)
{
    StorageNames names;
    Program p;
    p.handle_ = Handle<ProgramDeleter>(link(label, {compileStage(GL_COMPUTE_SHADER, path, defines, names)}));
    p.storage_ = assignStorageSlots(p.id(), label, names);
    return p;
}

void Program::use() const
{
    glUseProgram(id());
    useStorage(storage_);
}

const StorageLayout& Program::storage() const
{
    static const StorageLayout none;
    return storage_ ? *storage_ : none;
}

int Program::location(const std::string& name)
{
    auto it = locations_.find(name);
    if (it == locations_.end()) it = locations_.emplace(name, glGetUniformLocation(id(), name.c_str())).first;
    return it->second;
}

void Program::set(const std::string& n, int v)
{
    glProgramUniform1i(id(), location(n), v);
}
void Program::set(const std::string& n, unsigned v)
{
    glProgramUniform1ui(id(), location(n), v);
}
void Program::set(const std::string& n, float v)
{
    glProgramUniform1f(id(), location(n), v);
}
void Program::set(const std::string& n, const glm::vec2& v)
{
    glProgramUniform2fv(id(), location(n), 1, glm::value_ptr(v));
}
void Program::set(const std::string& n, const glm::vec3& v)
{
    glProgramUniform3fv(id(), location(n), 1, glm::value_ptr(v));
}
void Program::set(const std::string& n, const glm::vec4& v)
{
    glProgramUniform4fv(id(), location(n), 1, glm::value_ptr(v));
}
void Program::set(const std::string& n, const glm::ivec2& v)
{
    glProgramUniform2iv(id(), location(n), 1, glm::value_ptr(v));
}
void Program::set(const std::string& n, const glm::ivec3& v)
{
    glProgramUniform3iv(id(), location(n), 1, glm::value_ptr(v));
}
void Program::set(const std::string& n, const glm::mat3& v)
{
    glProgramUniformMatrix3fv(id(), location(n), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(const std::string& n, const glm::mat4& v)
{
    glProgramUniformMatrix4fv(id(), location(n), 1, GL_FALSE, glm::value_ptr(v));
}

} // namespace bounce::gl
