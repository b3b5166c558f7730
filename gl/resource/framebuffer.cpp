#include "gl/resource/framebuffer.h"

#include <stdexcept>
#include <vector>

#include "gl/debug.h"
#include "gl/gl.h"
#include "gl/resource/resource_error.h"
#include "gl/resource/texture.h"

namespace bounce::gl {

void FramebufferDeleter::operator()(unsigned id) const
{
    glDeleteFramebuffers(1, &id);
}
void VertexArrayDeleter::operator()(unsigned id) const
{
    glDeleteVertexArrays(1, &id);
}

Framebuffer::Framebuffer(const std::string& label) : label_(label)
{
    unsigned id = 0;
    glCreateFramebuffers(1, &id);
    handle_ = Handle<FramebufferDeleter>(id);
    labelObject(GL_FRAMEBUFFER, id, label);
}

void Framebuffer::attach(unsigned attachment, const Texture& texture, int level)
{
    glNamedFramebufferTexture(id(), attachment, texture.id(), level);
}

void Framebuffer::attachLayer(unsigned attachment, const Texture& texture, int layer, int level)
{
    glNamedFramebufferTextureLayer(id(), attachment, texture.id(), level, layer);
}

void Framebuffer::setDrawBuffers(std::initializer_list<unsigned> buffers)
{
    const std::vector<GLenum> b(buffers.begin(), buffers.end());
    glNamedFramebufferDrawBuffers(id(), GLsizei(b.size()), b.data());
}

void Framebuffer::setDefaultSize(int width, int height)
{
    glNamedFramebufferParameteri(id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
    glNamedFramebufferParameteri(id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
}

void Framebuffer::checkComplete() const
{
    const GLenum s = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
    if (s != GL_FRAMEBUFFER_COMPLETE)
        throw ResourceError(label_, "framebuffer '" + label_ + "' incomplete (status " + std::to_string(s) +
                                        "): an attachment could not be allocated or is over the driver's limits");
}

void Framebuffer::bind() const
{
    glBindFramebuffer(GL_FRAMEBUFFER, id());
}

VertexArray::VertexArray(const std::string& label)
{
    unsigned id = 0;
    glCreateVertexArrays(1, &id);
    handle_ = Handle<VertexArrayDeleter>(id);
    labelObject(GL_VERTEX_ARRAY, id, label);
}

void VertexArray::bind() const
{
    glBindVertexArray(id());
}

} // namespace bounce::gl
