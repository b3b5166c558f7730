#include "gl/frame/edge_antialias.h"

#include <array>

#include "gl/frame/bindings.h"
#include "gl/frame/frame.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

EdgeAntialias::EdgeAntialias()
    : edges_(Program::graphics("edge-aa.lines", "frame/edges.vert", "frame/edges.frag", {}, "frame/edges.geom")),
      resolve_(Program::graphics("edge-aa", "frame/fullscreen.vert", "frame/edge_aa.frag"))
{}

void EdgeAntialias::run(const Frame& frame, const Texture& image, PassTimers& timers)
{
    const int w = frame.width(), h = frame.height();
    if (!lines_ || lines_.width() != w || lines_.height() != h) {
        lines_ = Texture::create2D("edge-aa.lines", GL_RGBA32F, w, h);
        linesDepth_ = Texture::create2D("edge-aa.lines.depth", GL_DEPTH_COMPONENT32F, w, h);
        result_ = Texture::create2D("edge-aa", GL_RGBA32F, w, h);
        edgesFbo_.attach(GL_COLOR_ATTACHMENT0, lines_);
        edgesFbo_.attach(GL_DEPTH_ATTACHMENT, linesDepth_);
        edgesFbo_.checkComplete();
        resolveFbo_.attach(GL_COLOR_ATTACHMENT0, result_);
        resolveFbo_.checkComplete();
    }
    const GpuScene& scene = frame.gpuScene();
    {
        PassCost cost; // edges.frag per fragment of a strip: its depth against the G-buffer's, the line
        cost.flops = 10;
        cost.bytesRead = 8 + 4;
        cost.bytesWritten = 16 + 4;
        cost.triangles = double(scene.triangleCount());
        cost.bytesFixed = double(w) * h * 20 + 6.0 * scene.triangleCount() * 16.0; // clears, six corners each
        auto t = timers.scope("edge-aa.lines", cost);
        PassState state = PassState::fullscreen(edgesFbo_, w, h);
        state.depthTest = true; // the nearest edge: edges.frag's depth is its distance
        state.apply();
        const float none[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(edgesFbo_.id(), GL_COLOR, 0, none);
        glClearNamedFramebufferfv(edgesFbo_.id(), GL_DEPTH, 0, std::array<float, 1>{1.0f}.data());
        frame.bindGBuffer();
        edges_.set("viewProj", frame.projection() * frame.view());
        edges_.set("viewport", glm::vec2(float(w), float(h)));
        edges_.use();
        scene.drawWithAdjacency();
    }
    // edge_aa.frag per pixel: its line and light, and where an edge crosses it a neighbour's light and both
    // pixels' G-buffer.
    PassCost cost;
    cost.flops = 30;
    cost.fetches = 3;
    cost.bytesRead = 16 + 16;
    cost.bytesWritten = 16;
    auto t = timers.scope("edge-aa", cost);
    t.expectFragments(w, h);
    PassState::fullscreen(resolveFbo_, w, h).apply();
    frame.bindGBuffer();
    image.bind(UNIT_EDGE_IMAGE);
    lines_.bind(UNIT_EDGE_LINES);
    resolve_.use();
    frame.drawFullscreen();
}

} // namespace bounce::gl
