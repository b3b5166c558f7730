#include "app/demo_view.h"

#include <vector>

#include "gl/frame/bindings.h"
#include "gl/gl.h"

namespace bounce::app {

DemoView::DemoView()
    : program_(gl::Program::graphics("demo.tonemap", "frame/fullscreen.vert", "frame/tonemap.frag")), vao_("demo.view")
{}

void DemoView::draw(const gl::Texture& radiance, int x, int y, int w, int h, float exposureStops)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(x, y, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    radiance.bind(UNIT_TONEMAP_RADIANCE);
    program_.set("exposureStops", exposureStops);
    program_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void DemoView::upload(const core::Image& image, gl::Texture& texture)
{
    if (!texture || texture.width() != image.width || texture.height() != image.height) {
        texture = gl::Texture::create2D("demo.upload", GL_RGBA32F, image.width, image.height);
        texture.setFilter(GL_LINEAR, GL_LINEAR);
    }
    std::vector<float> rgba(std::size_t(image.width) * image.height * 4, 1.0f);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const glm::vec3 v = image.at(x, y);
            float* p = &rgba[(std::size_t(image.height - 1 - y) * image.width + x) * 4];
            p[0] = v.x;
            p[1] = v.y;
            p[2] = v.z;
        }
    glTextureSubImage2D(texture.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rgba.data());
}

} // namespace bounce::app
