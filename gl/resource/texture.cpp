#include "gl/resource/texture.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <stdexcept>

#include "gl/debug.h"
#include "gl/gl.h"
#include "gl/resource/resource_error.h"

namespace bounce::gl {

void TextureDeleter::operator()(unsigned id) const
{
    glDeleteTextures(1, &id);
}

std::size_t bytesPerTexel(unsigned f)
{
    switch (f) {
    case GL_R8:
    case GL_R8UI: return 1;
    case GL_RG8:
    case GL_R16F:
    case GL_DEPTH_COMPONENT16: return 2;
    case GL_RGBA8:
    case GL_SRGB8_ALPHA8:
    case GL_R32F:
    case GL_R32UI:
    case GL_R32I:
    case GL_RG16F:
    case GL_DEPTH_COMPONENT24:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH24_STENCIL8:
    case GL_RGB10_A2:
    case GL_R11F_G11F_B10F:
    case GL_RGBA8_SNORM: return 4;
    case GL_DEPTH32F_STENCIL8:
    case GL_RG32F:
    case GL_RGBA16F:
    case GL_RG32UI: return 8;
    case GL_RGB32F: return 12;
    case GL_RGBA32F:
    case GL_RGBA32UI: return 16;
    default: throw std::invalid_argument("bytesPerTexel: format not in the table");
    }
}

int mipLevelCount(int width, int height)
{
    const unsigned m = unsigned(std::max(1, std::max(width, height)));
    return int(std::bit_width(m));
}

namespace {

int glLimit(unsigned pname)
{
    GLint v = 0;
    glGetIntegerv(pname, &v);
    return v;
}

std::string describeSize(int w, int h, int layers, std::size_t bytes)
{
    return std::to_string(w) + "x" + std::to_string(h) +
           (layers > 1 ? " x " + std::to_string(layers) + " layers" : "") + ", " +
           std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB";
}

// Sizes over the driver's limits are refused before GL sees them (GL would answer GL_INVALID_VALUE and
// leave an unusable texture behind).
void checkLimits(const std::string& label, unsigned target, int w, int h, int layers, std::size_t bytes)
{
    const bool cube = target == GL_TEXTURE_CUBE_MAP || target == GL_TEXTURE_CUBE_MAP_ARRAY;
    const int maxSize = glLimit(cube ? GL_MAX_CUBE_MAP_TEXTURE_SIZE : GL_MAX_TEXTURE_SIZE);
    if (w < 1 || h < 1 || w > maxSize || h > maxSize)
        throw ResourceError(label, "texture '" + label + "' of " + describeSize(w, h, layers, bytes) +
                                       " exceeds the driver's maximum texture size " + std::to_string(maxSize));
    if ((target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_CUBE_MAP_ARRAY) &&
        layers > glLimit(GL_MAX_ARRAY_TEXTURE_LAYERS))
        throw ResourceError(label, "texture '" + label + "' of " + describeSize(w, h, layers, bytes) +
                                       " exceeds the driver's maximum of " +
                                       std::to_string(glLimit(GL_MAX_ARRAY_TEXTURE_LAYERS)) + " array layers");
}

// After glTextureStorage*: GL_OUT_OF_MEMORY (or any error) means the texture has no storage.
void checkStorage(const Texture& t, const std::string& label, std::size_t bytes)
{
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) return;
    throw ResourceError(
        label, "texture '" + label + "' of " + describeSize(t.width(), t.height(), t.layers(), bytes) +
                   " could not be allocated: " +
                   (e == GL_OUT_OF_MEMORY ? std::string("GL_OUT_OF_MEMORY") : "GL error 0x" + std::to_string(e)));
}

// Fills every level of new storage with a value no pass would write by chance (allocations.h), when
// poisoning is on. Errors are dropped: a driver may refuse to clear a multisample texture, and then it
// keeps its undefined contents.
void poisonStorage(const Texture& t)
{
    if (!poisonNewStorage()) return;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float floats[4] = {nan, nan, nan, nan}, ones[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    const unsigned uints[4] = {~0u, ~0u, ~0u, ~0u};
    const float depth = 0.5f;
    const unsigned depth24Stencil8 = 0x800000ffu; // depth 0.5 in the high 24 bits, stencil 255
    const struct {
        float depth;
        unsigned stencil;
    } depth32fStencil8 = {0.5f, 0xffu}; // FLOAT_32_UNSIGNED_INT_24_8_REV
    for (int level = 0; level < t.levels(); ++level) {
        switch (t.internalFormat()) {
        case GL_R16F:
        case GL_RG16F:
        case GL_RGBA16F:
        case GL_R32F:
        case GL_RG32F:
        case GL_RGB32F:
        case GL_RGBA32F:
        case GL_R11F_G11F_B10F: glClearTexImage(t.id(), level, GL_RGBA, GL_FLOAT, floats); break;
        case GL_R8:
        case GL_RG8:
        case GL_RGBA8:
        case GL_SRGB8_ALPHA8:
        case GL_RGB10_A2:
        case GL_RGBA8_SNORM: glClearTexImage(t.id(), level, GL_RGBA, GL_FLOAT, ones); break;
        case GL_R8UI:
        case GL_R32UI:
        case GL_RG32UI:
        case GL_RGBA32UI: glClearTexImage(t.id(), level, GL_RGBA_INTEGER, GL_UNSIGNED_INT, uints); break;
        case GL_R32I: glClearTexImage(t.id(), level, GL_RGBA_INTEGER, GL_INT, uints); break;
        case GL_DEPTH_COMPONENT16:
        case GL_DEPTH_COMPONENT24:
        case GL_DEPTH_COMPONENT32F: glClearTexImage(t.id(), level, GL_DEPTH_COMPONENT, GL_FLOAT, &depth); break;
        case GL_DEPTH24_STENCIL8:
            glClearTexImage(t.id(), level, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, &depth24Stencil8);
            break;
        case GL_DEPTH32F_STENCIL8:
            glClearTexImage(t.id(), level, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, &depth32fStencil8);
            break;
        default: break;
        }
    }
    while (glGetError() != GL_NO_ERROR) {}
}

} // namespace

Texture Texture::make(const std::string& label, unsigned target, unsigned format, int w, int h, int levels, int layers,
                      std::size_t texelBytes)
{
    std::size_t total = 0;
    for (int l = 0; l < levels; ++l)
        total += std::size_t(std::max(1, w >> l)) * std::size_t(std::max(1, h >> l)) * std::size_t(layers) * texelBytes;
    if (target != GL_TEXTURE_BUFFER) checkLimits(label, target, w, h, layers, total);
    while (glGetError() != GL_NO_ERROR) {} // what follows reads the storage call's own error
    Texture t;
    unsigned id = 0;
    glCreateTextures(target, 1, &id);
    t.handle_ = Handle<TextureDeleter>(id);
    t.target_ = target;
    t.format_ = format;
    t.width_ = w;
    t.height_ = h;
    t.levels_ = levels;
    t.layers_ = layers;
    std::size_t bytes = 0;
    for (int l = 0; l < levels; ++l)
        bytes += std::size_t(std::max(1, w >> l)) * std::size_t(std::max(1, h >> l)) * std::size_t(layers) * texelBytes;
    t.ticket_ = AllocationTicket(label, bytes);
    labelObject(GL_TEXTURE, id, label);
    return t;
}

Texture Texture::create2D(const std::string& label, unsigned f, int w, int h, int levels)
{
    Texture t = make(label, GL_TEXTURE_2D, f, w, h, levels, 1, bytesPerTexel(f));
    glTextureStorage2D(t.id(), levels, f, w, h);
    checkStorage(t, label,
                 std::size_t(t.width()) * std::size_t(t.height()) * std::size_t(t.layers()) * bytesPerTexel(f));
    poisonStorage(t);
    t.setFilter(levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST, GL_NEAREST);
    t.setWrap(GL_CLAMP_TO_EDGE);
    return t;
}

Texture Texture::create2DArray(const std::string& label, unsigned f, int w, int h, int layers)
{
    Texture t = make(label, GL_TEXTURE_2D_ARRAY, f, w, h, 1, layers, bytesPerTexel(f));
    glTextureStorage3D(t.id(), 1, f, w, h, layers);
    checkStorage(t, label,
                 std::size_t(t.width()) * std::size_t(t.height()) * std::size_t(t.layers()) * bytesPerTexel(f));
    poisonStorage(t);
    t.setFilter(GL_NEAREST, GL_NEAREST);
    t.setWrap(GL_CLAMP_TO_EDGE);
    return t;
}

Texture Texture::createCube(const std::string& label, unsigned f, int size)
{
    Texture t = make(label, GL_TEXTURE_CUBE_MAP, f, size, size, 1, 6, bytesPerTexel(f));
    glTextureStorage2D(t.id(), 1, f, size, size);
    checkStorage(t, label,
                 std::size_t(t.width()) * std::size_t(t.height()) * std::size_t(t.layers()) * bytesPerTexel(f));
    poisonStorage(t);
    t.setFilter(GL_NEAREST, GL_NEAREST);
    t.setWrap(GL_CLAMP_TO_EDGE);
    return t;
}

Texture Texture::createCubeArray(const std::string& label, unsigned f, int size, int cubes)
{
    Texture t = make(label, GL_TEXTURE_CUBE_MAP_ARRAY, f, size, size, 1, 6 * cubes, bytesPerTexel(f));
    glTextureStorage3D(t.id(), 1, f, size, size, 6 * cubes);
    checkStorage(t, label,
                 std::size_t(t.width()) * std::size_t(t.height()) * std::size_t(t.layers()) * bytesPerTexel(f));
    poisonStorage(t);
    t.setFilter(GL_NEAREST, GL_NEAREST);
    t.setWrap(GL_CLAMP_TO_EDGE);
    return t;
}

Texture Texture::create2DMultisample(const std::string& label, unsigned f, int w, int h, int samples)
{
    Texture t = make(label, GL_TEXTURE_2D_MULTISAMPLE, f, w, h, 1, samples, bytesPerTexel(f));
    glTextureStorage2DMultisample(t.id(), samples, f, w, h, GL_TRUE);
    checkStorage(t, label,
                 std::size_t(t.width()) * std::size_t(t.height()) * std::size_t(t.layers()) * bytesPerTexel(f));
    poisonStorage(t);
    return t;
}

Texture Texture::create2DMultisampleArray(const std::string& label, unsigned f, int w, int h, int samples, int layers)
{
    Texture t = make(label, GL_TEXTURE_2D_MULTISAMPLE_ARRAY, f, w, h, 1, samples * layers, bytesPerTexel(f));
    t.layers_ = layers;
    glTextureStorage3DMultisample(t.id(), samples, f, w, h, layers, GL_TRUE);
    checkStorage(t, label, std::size_t(w) * std::size_t(h) * std::size_t(samples * layers) * bytesPerTexel(f));
    poisonStorage(t);
    return t;
}

Texture Texture::createBufferView(const std::string& label, unsigned f, const Buffer& buffer)
{
    const std::size_t texels = buffer.bytes() / bytesPerTexel(f);
    GLint maxTexels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    if (texels > std::size_t(std::max(maxTexels, 0)))
        throw std::invalid_argument(label + ": " + std::to_string(texels) +
                                    " texels exceed GL_MAX_TEXTURE_BUFFER_SIZE (" + std::to_string(maxTexels) + ")");
    Texture t = make(label, GL_TEXTURE_BUFFER, f, int(texels), 1, 1, 1, 0); // the buffer is counted already
    glTextureBuffer(t.id(), f, buffer.id());
    return t;
}

void Texture::setFilter(unsigned minFilter, unsigned magFilter)
{
    glTextureParameteri(id(), GL_TEXTURE_MIN_FILTER, GLint(minFilter));
    glTextureParameteri(id(), GL_TEXTURE_MAG_FILTER, GLint(magFilter));
}

void Texture::setWrap(unsigned wrap)
{
    glTextureParameteri(id(), GL_TEXTURE_WRAP_S, GLint(wrap));
    glTextureParameteri(id(), GL_TEXTURE_WRAP_T, GLint(wrap));
    glTextureParameteri(id(), GL_TEXTURE_WRAP_R, GLint(wrap));
}

void Texture::setCompare(bool enabled)
{
    glTextureParameteri(id(), GL_TEXTURE_COMPARE_MODE, enabled ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
    glTextureParameteri(id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}

void Texture::generateMipmap()
{
    glGenerateTextureMipmap(id());
}

void Texture::bind(unsigned unit) const
{
    glBindTextureUnit(unit, id());
}

void Texture::bindImage(unsigned unit, unsigned access, int level, unsigned format) const
{
    const bool layered = target_ != GL_TEXTURE_2D;
    glBindImageTexture(unit, id(), level, layered ? GL_TRUE : GL_FALSE, 0, access, format ? format : format_);
}

void Texture::clear(int level, const float rgba[4])
{
    const bool depth =
        format_ == GL_DEPTH_COMPONENT32F || format_ == GL_DEPTH_COMPONENT24 || format_ == GL_DEPTH_COMPONENT16;
    glClearTexImage(id(), level, depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, rgba);
}

std::vector<float> Texture::readFloats(int level, int components) const
{
    static const unsigned kFormats[] = {GL_RED, GL_RED, GL_RG, GL_RGB, GL_RGBA};
    const int w = std::max(1, width_ >> level), h = std::max(1, height_ >> level);
    const unsigned baseFormat =
        (format_ == GL_DEPTH_COMPONENT32F || format_ == GL_DEPTH_COMPONENT24 || format_ == GL_DEPTH_COMPONENT16)
            ? GL_DEPTH_COMPONENT
            : kFormats[components];
    std::vector<float> out(std::size_t(w) * std::size_t(h) * std::size_t(layers_) * std::size_t(components));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(id(), level, baseFormat, GL_FLOAT, GLsizei(out.size() * sizeof(float)), out.data());
    return out;
}

} // namespace bounce::gl
