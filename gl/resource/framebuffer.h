// Framebuffers and vertex arrays (DSA), labelled. Attachments are owned by the caller.
#pragma once

#include <initializer_list>
#include <string>

#include "gl/resource/handle.h"

namespace bounce::gl {

class Texture;

struct FramebufferDeleter {
    void operator()(unsigned id) const;
};
struct VertexArrayDeleter {
    void operator()(unsigned id) const;
};

class Framebuffer {
public:
    Framebuffer() = default;
    explicit Framebuffer(const std::string& label);
    unsigned id() const { return handle_.id(); }
    // attachment: GL_COLOR_ATTACHMENTi, GL_DEPTH_ATTACHMENT, GL_DEPTH_STENCIL_ATTACHMENT.
    void attach(unsigned attachment, const Texture& texture, int level = 0);
    void attachLayer(unsigned attachment, const Texture& texture, int layer, int level = 0);
    void setDrawBuffers(std::initializer_list<unsigned> buffers);
    // A framebuffer without attachments (passes that only write images) rasterises this size.
    void setDefaultSize(int width, int height);
    // Throws std::runtime_error naming the label when incomplete.
    void checkComplete() const;
    void bind() const;

private:
    Handle<FramebufferDeleter> handle_;
    std::string label_;
};

class VertexArray {
public:
    VertexArray() = default;
    explicit VertexArray(const std::string& label);
    unsigned id() const { return handle_.id(); }
    void bind() const;

private:
    Handle<VertexArrayDeleter> handle_;
};

} // namespace bounce::gl
