#include "gl/resource/buffer.h"

#include "gl/debug.h"
#include "gl/gl.h"
#include "gl/resource/storage_bindings.h"

namespace bounce::gl {

void BufferDeleter::operator()(unsigned id) const
{
    forgetStorageBuffer(id);
    glDeleteBuffers(1, &id);
}

Buffer::Buffer(const std::string& label, std::size_t bytes, const void* data) : bytes_(bytes), ticket_(label, bytes)
{
    unsigned id = 0;
    glCreateBuffers(1, &id);
    handle_ = Handle<BufferDeleter>(id);
    // Zero-sized storage is an error in GL; keep one word so empty scenes still bind something.
    glNamedBufferStorage(id, GLsizeiptr(bytes ? bytes : 4), data, GL_DYNAMIC_STORAGE_BIT);
    labelObject(GL_BUFFER, id, label);
    if (!data && poisonNewStorage()) {
        const unsigned char poison = 0xff; // bytes: a storage size need not be a multiple of four
        glClearNamedBufferData(id, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &poison);
    }
}

void Buffer::update(std::size_t offset, std::size_t bytes, const void* data)
{
    if (bytes) glNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

void Buffer::download(std::size_t offset, std::size_t bytes, void* out) const
{
    if (bytes) glGetNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), out);
}

void Buffer::clearToZero()
{
    const unsigned zero = 0;
    glClearNamedBufferData(id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

void Buffer::bindBase(unsigned target, unsigned index) const
{
    if (target == GL_SHADER_STORAGE_BUFFER)
        bindStorage(index, id()); // a storage name, bound by the programs that read it (storage_bindings.h)
    else
        glBindBufferBase(target, index, id());
}

} // namespace bounce::gl
