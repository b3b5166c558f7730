// Moving frames' edge antialiasing (frame parameter `edgeAA`, on by default): a moving frame samples each
// pixel at its centre, so every edge of the geometry (silhouettes, creases, a surface's boundary) shows the one
// surface the centre falls on, where the box-filtered pixel that still frames converge to mixes both by area.
// Along a straight edge that error has one sign for the whole edge (set by the edge's sub-pixel offset), and
// no temporal reuse of pixel-centred frames averages it. Two passes after the composite, in every frame that
// is not a still frame (still frames jitter their pixels and average them, and are left as they are):
//   - edges: the scene drawn again with its triangles' neighbours (GpuScene::drawWithAdjacency); a geometry
//     shader gives each triangle's edges that bound a surface on screen (a boundary, a silhouette: the
//     neighbour faces the other way, a crease: normals over about 25 degrees apart) as lines in window
//     coordinates, and each pixel keeps, for the triangle the G-buffer sees there (matched by eye depth, so
//     alpha-masked holes and hidden triangles write nothing), the nearest: its outward normal and its
//     distance from the pixel's centre (glsl/frame/edges.*);
//   - resolve (glsl/frame/edge_aa.frag): the area of the pixel beyond that edge, in closed form for a
//     straight edge, takes the light of the neighbour across it where that neighbour is another surface and
//     not a nearer one; a pixel that a nearer neighbour's edge runs into takes that neighbour's light over
//     the area the edge's line gives it.
// Distance-to-edge antialiasing (Malan, "Edge Antialiasing by Post-Processing", GPU Pro, 2010), with the
// covered area exact for one straight edge instead of a linear ramp, and edges inside smooth surfaces left
// out by the adjacency (a triangle's diagonal inside a wall would otherwise mix the wall with whatever lies
// beyond the wall's real edge near a corner). What it cannot know: triangles smaller than a pixel, several
// edges in one pixel (the nearest alone counts), alpha-masked outlines (the texture's, not a triangle's),
// edges inside one triangle (shadow edges, texture edges), and the far side's light where the neighbour
// across does not show it.
#pragma once

#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class Frame;

class EdgeAntialias {
public:
    EdgeAntialias();
    // Writes result() from `image` (the frame's composited light) with the frame's G-buffer and camera; the
    // frame must be at its full size (outside beginIndirect).
    void run(const Frame& frame, const Texture& image, PassTimers& timers);
    const Texture& result() const { return result_; }

private:
    Program edges_, resolve_;
    Framebuffer edgesFbo_{"edge-aa.lines.fbo"}, resolveFbo_{"edge-aa.fbo"};
    // lines_: the edges pass's target (RGBA32F: the nearest bounding edge's unit normal out of its triangle,
    // the signed distance of the pixel's centre from it, positive on the triangle's side, and 1 where
    // written); linesDepth_ its depth test's.
    Texture lines_, linesDepth_, result_;
};

} // namespace bounce::gl
