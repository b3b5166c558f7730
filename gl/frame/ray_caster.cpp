#include "gl/frame/ray_caster.h"

#include <algorithm>
#include <string>

#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

PassCost closestHitWork(const RayCaster& caster, double rays)
{
    constexpr double kFlopsRaySetup = 200;                 // bvhRay: six corrected divisions
    constexpr double kFlopsBox = 25, kFlopsTriangle = 100; // bvhHitBox, bvhHitTriangle
    constexpr double kBoxBytes = 32, kTriangleBytes = 48;  // core::BvhNode, core::BvhTriangle
    const double boxes = 2.0 * caster.bvh().depth(), triangles = 2.0 * core::Bvh::kMaxLeafSize;
    PassCost w;
    w.flopsFixed = rays * (kFlopsRaySetup + boxes * kFlopsBox + triangles * kFlopsTriangle);
    w.bytesFixed = rays * (boxes * kBoxBytes + triangles * kTriangleBytes);
    return w;
}

RayCaster::RayCaster(const core::Scene& scene) : bvh_(scene), hasAlphaMask_(scene.hasAlphaMask())
{
    nodes_ = Buffer::fromVector("raycast.bvhNodes", bvh_.nodes());
    // An SSBO may not be empty: a scene without triangles gets one that no leaf names.
    triangles_ = bvh_.triangles().empty() ? Buffer("raycast.bvhTriangles", sizeof(core::BvhTriangle))
                                          : Buffer::fromVector("raycast.bvhTriangles", bvh_.triangles());
}

void RayCaster::bind() const
{
    nodes_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_BVH_NODES);
    triangles_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_BVH_TRIANGLES);
}

std::vector<Define> RayCaster::defines() const
{
    if (!hasAlphaMask_) return {};
    return {{"ALPHA_MASK", "1"}};
}

RayBatch::RayBatch(const std::vector<Define>& defines)
    : compute_(Program::compute("raycast.batch.compute", "frame/raycast_batch.comp", defines)),
      fragment_(
          Program::graphics("raycast.batch.fragment", "frame/fullscreen.vert", "frame/raycast_batch.frag", defines)),
      vao_("raycast.batch")
{}

void RayBatch::upload(const std::vector<BatchRay>& rays)
{
    count_ = rays.size();
    const std::size_t n = std::max<std::size_t>(count_, 1);
    rays_ =
        rays.empty() ? Buffer("raycast.batch.rays", sizeof(BatchRay)) : Buffer::fromVector("raycast.batch.rays", rays);
    results_ = Buffer("raycast.batch.results", n * sizeof(BatchResult));
    results_.clearToZero();
    const int width = int(std::min<std::size_t>(n, kFragmentWidth));
    const int height = int((n + std::size_t(width) - 1) / std::size_t(width));
    if (width != width_ || height != height_) {
        width_ = width;
        height_ = height;
        target_ = Texture::create2D("raycast.batch.target", GL_R8, width, height);
        framebuffer_ = Framebuffer("raycast.batch");
        framebuffer_.attach(GL_COLOR_ATTACHMENT0, target_);
        framebuffer_.checkComplete();
    }
}

void RayBatch::cast(const RayCaster& caster, RayStage stage, int queries)
{
    caster.bind();
    rays_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_RAY_BATCH_RAYS);
    results_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_RAY_BATCH_RESULTS);
    Program& p = stage == RayStage::Compute ? compute_ : fragment_;
    p.set("rayCount", unsigned(count_));
    p.use();
    // One query per pass (raycast_batch.glsl says why).
    for (int query : {kQueryClosest, kQueryAny}) {
        if (!(queries & query)) continue;
        p.set("queries", query);
        if (stage == RayStage::Compute) {
            glDispatchCompute(GLuint((count_ + 63) / 64), 1, 1);
        } else {
            p.set("batchWidth", width_);
            PassState::fullscreen(framebuffer_, width_, height_).apply();
            vao_.bind();
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glFinish();
}

std::vector<BatchResult> RayBatch::results() const
{
    std::vector<BatchResult> r = results_.download<BatchResult>();
    r.resize(count_);
    return r;
}

std::vector<BatchResult> RayBatch::run(const RayCaster& caster, const std::vector<BatchRay>& rays, RayStage stage,
                                       int queries)
{
    upload(rays);
    cast(caster, stage, queries);
    return results();
}

} // namespace bounce::gl
