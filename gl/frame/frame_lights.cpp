#include "gl/frame/frame_lights.h"

#include "gl/frame/bindings.h"
#include "gl/gl.h"

namespace bounce::gl {

void FrameLights::set(const std::vector<GpuLight>& lights)
{
    lights_ = lights;
    Buffer::assign(buffer_, "lights", lights.empty() ? std::vector<GpuLight>(1) : lights);
}

void FrameLights::bind() const
{
    buffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_LIGHTS);
}

} // namespace bounce::gl
