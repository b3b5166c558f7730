// Display helpers of the demo: tone-mapped blits of a radiance texture into part of the window, and the
// comparison of two images (difference heat map, relative RMSE).
#pragma once

#include "core/image.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"

namespace bounce::app {

class DemoView {
public:
    DemoView();
    // Draws `radiance` tone mapped into the window rectangle (x, y, w, h), GL window coordinates.
    void draw(const gl::Texture& radiance, int x, int y, int w, int h, float exposureStops);
    // Uploads a CPU image (row 0 at the top) into an RGBA32F texture, reallocating when the size changes.
    static void upload(const core::Image& image, gl::Texture& texture);

private:
    gl::Program program_;
    gl::VertexArray vao_;
};

} // namespace bounce::app
