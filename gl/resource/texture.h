// GL textures (DSA, immutable storage), labelled and counted in Allocations.
#pragma once

#include <string>
#include <vector>

#include "gl/resource/allocations.h"
#include "gl/resource/buffer.h"
#include "gl/resource/handle.h"

namespace bounce::gl {

struct TextureDeleter {
    void operator()(unsigned id) const;
};

class Texture {
public:
    Texture() = default;
    static Texture create2D(const std::string& label, unsigned internalFormat, int width, int height, int levels = 1);
    static Texture create2DArray(const std::string& label, unsigned internalFormat, int width, int height, int layers);
    static Texture createCube(const std::string& label, unsigned internalFormat, int size);
    // A cube-map array of `cubes` cubes (one per point light).
    static Texture createCubeArray(const std::string& label, unsigned internalFormat, int size, int cubes);
    static Texture create2DMultisample(const std::string& label, unsigned internalFormat, int width, int height,
                                       int samples);
    // `layers` multisample layers of `samples` samples each (the stencil-routed k-buffer's slices).
    static Texture create2DMultisampleArray(const std::string& label, unsigned internalFormat, int width, int height,
                                            int samples, int layers);
    // A buffer texture (samplerBuffer) over the whole of `buffer`, read as texels of `internalFormat`: a
    // view, it allocates nothing. Throws std::invalid_argument beyond GL_MAX_TEXTURE_BUFFER_SIZE texels.
    static Texture createBufferView(const std::string& label, unsigned internalFormat, const Buffer& buffer);

    unsigned id() const { return handle_.id(); }
    explicit operator bool() const { return bool(handle_); }
    unsigned target() const { return target_; }
    unsigned internalFormat() const { return format_; }
    int width() const { return width_; }
    int height() const { return height_; }
    int levels() const { return levels_; }
    int layers() const { return layers_; }

    // Sampler state on the texture object itself.
    void setFilter(unsigned minFilter, unsigned magFilter);
    void setWrap(unsigned wrap);
    void setCompare(bool enabled); // depth comparison for PCF (GL_LEQUAL)
    void generateMipmap();
    void bind(unsigned unit) const;
    void bindImage(unsigned unit, unsigned access, int level = 0, unsigned format = 0) const;
    void clear(int level, const float rgba[4]);
    // Reads one level back as floats (components per texel from the format: 1..4).
    std::vector<float> readFloats(int level = 0, int components = 4) const;

private:
    Handle<TextureDeleter> handle_;
    unsigned target_ = 0, format_ = 0;
    int width_ = 0, height_ = 0, levels_ = 1, layers_ = 1;
    AllocationTicket ticket_;
    static Texture make(const std::string& label, unsigned target, unsigned format, int w, int h, int levels,
                        int layers, std::size_t texelBytes);
};

// Bytes per texel of the sized internal formats Bounce uses.
std::size_t bytesPerTexel(unsigned internalFormat);
// Number of mip levels of a full chain for a width x height image (1x1 gives 1).
int mipLevelCount(int width, int height);

} // namespace bounce::gl
