#include "gl/frame/frame_lights.h"

#include <algorithm>
#include <cstring>

#include "gl/frame/bindings.h"
#include "gl/gl.h"

namespace bounce::gl {

void FrameLights::set(const std::vector<GpuLight>& lights, const std::vector<GpuShadowView>& views,
                      const std::vector<glm::vec4>& polygons)
{
    lights_ = lights;
    constexpr std::size_t lightVec4s = sizeof(GpuLight) / sizeof(glm::vec4);
    constexpr std::size_t viewVec4s = sizeof(GpuShadowView) / sizeof(glm::vec4);
    const std::size_t viewsAt = lights.size() * lightVec4s, polygonsAt = viewsAt + views.size() * viewVec4s;
    std::vector<glm::vec4> data(1 + polygonsAt + polygons.size());
    const glm::ivec4 header(int(viewsAt), int(polygonsAt), int(lights.size()), int(views.size()));
    std::memcpy(&data[0], &header, sizeof(header));
    if (!lights.empty()) std::memcpy(&data[1], lights.data(), lights.size() * sizeof(GpuLight));
    if (!views.empty()) std::memcpy(&data[1 + viewsAt], views.data(), views.size() * sizeof(GpuShadowView));
    std::copy(polygons.begin(), polygons.end(), data.begin() + std::ptrdiff_t(1 + polygonsAt));
    Buffer::assign(buffer_, "lights", data);
}

void FrameLights::bind() const
{
    buffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_LIGHTS);
}

} // namespace bounce::gl
