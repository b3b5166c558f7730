#include "gl/technique/grb/grb_atlas.h"

#include <vector>

#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"
#include "gl/technique/grb/bindings.h"

namespace bounce::gl {

GrbAtlas::GrbAtlas(const core::Scene& scene, const core::AtlasSettings& settings)
    : atlas_(core::buildAtlas(scene, settings)),
      fbo_("grb.atlas.fbo"),
      vao_("grb.atlas.fill"),
      program_(Program::graphics("grb.atlas", "technique/grb/atlas_fill.vert", "technique/grb/atlas_fill.frag"))
{
    std::vector<glm::vec2> corners;
    corners.reserve(atlas_.corners.size() * 3);
    for (const auto& c : atlas_.corners) corners.insert(corners.end(), c.begin(), c.end());
    corners_ = Buffer::fromVector("grb.atlas.corners", corners);
    charts_ = Buffer::fromVector("grb.atlas.triangleCharts", atlas_.triangleChart);
    const int w = atlas_.width, h = atlas_.height;
    position_ = Texture::create2D("grb.atlas.position", GL_RGBA32F, w, h);
    normal_ = Texture::create2D("grb.atlas.normal", GL_RGBA32F, w, h);
    baseColor_ = Texture::create2D("grb.atlas.baseColor", GL_RGBA32F, w, h);
    depth_ = Texture::create2D("grb.atlas.fillDepth", GL_DEPTH_COMPONENT32F, w, h);
    fbo_.attach(GL_COLOR_ATTACHMENT0, position_);
    fbo_.attach(GL_COLOR_ATTACHMENT1, normal_);
    fbo_.attach(GL_COLOR_ATTACHMENT2, baseColor_);
    fbo_.attach(GL_DEPTH_ATTACHMENT, depth_);
    fbo_.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2});
    fbo_.checkComplete();
}

void GrbAtlas::bind() const
{
    corners_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_GRB_ATLAS_CORNERS);
    position_.bind(UNIT_GRB_POSITION);
    normal_.bind(UNIT_GRB_NORMAL);
    baseColor_.bind(UNIT_GRB_BASE_COLOR);
}

void GrbAtlas::fill(const Frame& frame, PassTimers& timers)
{
    {
        // atlas_fill.frag per fragment of a triangle's quad: its three corners, the inside test, and at most
        // (a bound: every fragment outside the triangle and kept) the nearest point on the edges, then the
        // triangle's indices, positions, normals, uvs, material (64 bytes) and chart, the normals and point,
        // with textures one bilinear base-colour sample, three RGBA32F out and the depth test. Per scope the
        // clears, and atlas_fill.vert's six corners per scene triangle, each reading its three atlas corners.
        const double texels = double(atlas_.width) * atlas_.height, triangles = double(atlas_.triangleCount());
        const bool textured = frame.gpuScene().hasTextures();
        PassCost cost;
        cost.flops = 25 + 75 + 110;
        cost.fetches = textured ? 4 : 0;
        cost.bytesRead = 3 * 8 + 3 * (4 + 12 + 12 + 8) + 4 + 64 + 4 + (textured ? 4 * 4 : 0) + 4;
        cost.bytesWritten = 3 * 16 + 4;
        cost.bytesFixed = texels * (3 * 16 + 4) + 6.0 * triangles * 3 * 8;
        cost.triangles = 2 * triangles;
        auto t = timers.scope("atlas", cost);
        PassState s = PassState::fullscreen(fbo_, atlas_.width, atlas_.height);
        s.depthTest = true; // the nearest triangle owns a texel (atlas_fill.frag)
        s.apply();
        const float zero[4] = {0, 0, 0, 0};
        for (int i = 0; i < 3; ++i) glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, i, zero);
        glClearNamedFramebufferfi(fbo_.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
        frame.bindSceneData();
        corners_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_GRB_ATLAS_CORNERS);
        charts_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_GRB_TRIANGLE_CHART);
        frame.gpuScene().baseColorTextures().bind(UNIT_BASE_COLOR);
        program_.set("atlasSize", glm::vec2(float(atlas_.width), float(atlas_.height)));
        program_.set("fillMargin", core::kFillMargin);
        program_.use();
        vao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(6 * atlas_.triangleCount()));
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    const std::vector<float> p = position_.readFloats(0, 4);
    filled_ = 0;
    for (std::size_t i = 3; i < p.size(); i += 4) filled_ += p[i] != 0.0f;
}

} // namespace bounce::gl
