#include "gl/resource/storage_bindings.h"

#include <algorithm>
#include <cctype>
#include <unordered_map>

#include "gl/gl.h"
#include "gl/resource/program.h"

namespace bounce::gl {

namespace {

bool identifierChar(char c)
{
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

std::size_t skipSpace(const std::string& s, std::size_t p)
{
    while (p < s.size() && std::isspace(static_cast<unsigned char>(s[p]))) ++p;
    return p;
}

std::string identifierAt(const std::string& s, std::size_t p)
{
    std::size_t e = p;
    while (e < s.size() && identifierChar(s[e])) ++e;
    return s.substr(p, e - p);
}

std::string trim(const std::string& s)
{
    const auto a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

bool allDigits(const std::string& s)
{
    return !s.empty() &&
           std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

// Every "#define NAME value" of a preprocessed stage (the bindings.glsl files it includes, the injected
// defines), value's first token; a name defined twice with different values (in two branches) maps to "",
// which no binding may use.
std::map<std::string, std::string> objectDefines(const std::string& src)
{
    std::map<std::string, std::string> defines;
    std::size_t line = 0;
    while (line < src.size()) {
        std::size_t end = src.find('\n', line);
        if (end == std::string::npos) end = src.size();
        std::size_t p = skipSpace(src, line);
        if (p < end && src[p] == '#') {
            p = skipSpace(src, p + 1);
            if (identifierAt(src, p) == "define") {
                p = skipSpace(src, p + 6);
                const std::string name = identifierAt(src, p);
                const std::string rest = src.substr(p + name.size(), end - p - name.size()); // this line's
                const std::string value = !rest.empty() && rest[0] != '(' ? identifierAt(rest, skipSpace(rest, 0)) : "";
                if (const auto [it, fresh] = defines.emplace(name, value); !fresh && it->second != value)
                    it->second.clear();
            }
        }
        line = end + 1;
    }
    return defines;
}

unsigned resolve(const std::string& token, const std::map<std::string, std::string>& defines, const std::string& where)
{
    std::string t = token;
    for (int depth = 0; depth < 8 && !t.empty(); ++depth) {
        if (allDigits(t)) return unsigned(std::stoul(t));
        const auto it = defines.find(t);
        if (it == defines.end()) break;
        t = it->second;
    }
    throw ShaderError(where + ": storage binding '" + token +
                      "' is not a number, nor a name defined once as one (SSBO_* in a bindings.glsl)");
}

std::vector<std::shared_ptr<const StorageLayout>>& linked()
{
    static std::vector<std::shared_ptr<const StorageLayout>> layouts;
    return layouts;
}

// The context's storage table: name -> GL buffer, and the layout of the program in use.
struct StorageTable {
    std::unordered_map<unsigned, unsigned> buffers;
    std::shared_ptr<const StorageLayout> current;
};

StorageTable& table()
{
    static StorageTable t;
    return t;
}

} // namespace

std::string takeStorageNames(const std::string& src, const std::string& path, StorageNames& names)
{
    const std::map<std::string, std::string> defines = objectDefines(src);
    std::string out;
    out.reserve(src.size());
    std::size_t copied = 0;
    for (std::size_t p = src.find("layout"); p != std::string::npos; p = src.find("layout", p + 1)) {
        if ((p > 0 && identifierChar(src[p - 1])) || identifierChar(src[std::min(p + 6, src.size() - 1)])) continue;
        const std::size_t open = skipSpace(src, p + 6);
        if (open >= src.size() || src[open] != '(') continue;
        const std::size_t close = src.find(')', open);
        if (close == std::string::npos) break;
        // The qualifiers after the layout, up to the block's name: `readonly buffer Name`.
        std::string block;
        for (std::size_t q = skipSpace(src, close + 1);;) {
            const std::string word = identifierAt(src, q);
            if (word.empty()) break;
            q = skipSpace(src, q + word.size());
            if (word == "buffer") {
                block = identifierAt(src, q);
                break;
            }
        }
        if (block.empty()) continue;
        const std::size_t lineNo = std::size_t(std::count(src.begin(), src.begin() + std::ptrdiff_t(p), '\n')) + 1;
        const std::string where = path + " (preprocessed line " + std::to_string(lineNo) + ", block " + block + ")";
        // The layout's items without the binding.
        std::vector<std::string> kept;
        std::string binding;
        const std::string args = src.substr(open + 1, close - open - 1);
        std::size_t from = 0;
        while (from <= args.size()) {
            std::size_t comma = args.find(',', from);
            if (comma == std::string::npos) comma = args.size();
            const std::string item = trim(args.substr(from, comma - from));
            if (identifierAt(item, 0) == "binding") {
                const auto eq = item.find('=');
                binding = eq == std::string::npos ? std::string() : trim(item.substr(eq + 1));
            } else if (!item.empty()) {
                kept.push_back(item);
            }
            from = comma + 1;
        }
        if (binding.empty()) throw ShaderError(where + ": a storage block needs `binding = SSBO_NAME`");
        const unsigned name = resolve(binding, defines, where);
        if (const auto [it, fresh] = names.emplace(block, name); !fresh && it->second != name)
            throw ShaderError(where + ": block " + block + " is declared with two storage names (" +
                              std::to_string(it->second) + " and " + std::to_string(name) +
                              "); give each its own block name");
        // The same lines: a layout over several lines keeps its line breaks.
        const std::string breaks(std::size_t(std::count(args.begin(), args.end(), '\n')), '\n');
        out.append(src, copied, p - copied);
        if (!kept.empty()) {
            out += "layout(";
            for (std::size_t i = 0; i < kept.size(); ++i) out += (i ? ", " : "") + kept[i];
            out += breaks + ")";
        } else {
            out += breaks;
        }
        copied = close + 1;
        p = close;
    }
    out.append(src, copied, std::string::npos);
    return out;
}

std::shared_ptr<const StorageLayout> assignStorageSlots(unsigned program, const std::string& label,
                                                        const StorageNames& names)
{
    auto layout = std::make_shared<StorageLayout>();
    layout->label = label;
    GLint count = 0;
    glGetProgramInterfaceiv(program, GL_SHADER_STORAGE_BLOCK, GL_ACTIVE_RESOURCES, &count);
    GLint longest = 0;
    glGetProgramInterfaceiv(program, GL_SHADER_STORAGE_BLOCK, GL_MAX_NAME_LENGTH, &longest);
    std::vector<std::pair<StorageBlock, unsigned>> blocks; // and the block's index
    for (GLint i = 0; i < count; ++i) {
        std::string block(std::size_t(std::max(longest, 1)), '\0');
        GLsizei length = 0;
        glGetProgramResourceName(program, GL_SHADER_STORAGE_BLOCK, GLuint(i), GLsizei(block.size()), &length,
                                 block.data());
        block.resize(std::size_t(length));
        const auto it = names.find(block);
        if (it == names.end())
            throw ShaderError("program '" + label + "': storage block " + block + " has no storage name");
        blocks.push_back({{block, it->second, 0}, unsigned(i)});
    }
    std::sort(blocks.begin(), blocks.end(), [](const auto& a, const auto& b) { return a.first.name < b.first.name; });
    for (std::size_t i = 0; i < blocks.size(); ++i) {
        StorageBlock& b = blocks[i].first;
        if (i > 0 && blocks[i - 1].first.name == b.name)
            throw ShaderError("program '" + label + "': storage blocks " + blocks[i - 1].first.block + " and " +
                              b.block + " are both bound by name " + std::to_string(b.name));
        b.slot = unsigned(i);
        glShaderStorageBlockBinding(program, blocks[i].second, b.slot);
        layout->blocks.push_back(b);
    }

    linked().push_back(layout);
    return layout;
}

const std::vector<std::shared_ptr<const StorageLayout>>& linkedStorageLayouts()
{
    return linked();
}

void resetLinkedStorageLayouts()
{
    linked().clear();
}

void bindStorage(unsigned name, unsigned buffer)
{
    StorageTable& t = table();
    t.buffers[name] = buffer;
    if (!t.current) return;
    for (const StorageBlock& b : t.current->blocks)
        if (b.name == name) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.slot, buffer);
}

void forgetStorageBuffer(unsigned buffer)
{
    StorageTable& t = table();
    for (auto it = t.buffers.begin(); it != t.buffers.end();)
        it = it->second == buffer ? t.buffers.erase(it) : std::next(it);
}

void useStorage(std::shared_ptr<const StorageLayout> layout)
{
    StorageTable& t = table();
    t.current = std::move(layout);
    if (!t.current) return;
    for (const StorageBlock& b : t.current->blocks) {
        const auto it = t.buffers.find(b.name);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b.slot, it == t.buffers.end() ? 0u : it->second);
    }
}

std::string unboundStorage(const StorageLayout& layout)
{
    const StorageTable& t = table();
    std::string unbound;
    for (const StorageBlock& b : layout.blocks)
        if (!t.buffers.count(b.name))
            unbound += (unbound.empty() ? "" : ", ") + b.block + " (storage name " + std::to_string(b.name) + ")";
    return unbound;
}

} // namespace bounce::gl
