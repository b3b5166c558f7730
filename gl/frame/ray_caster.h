// GPU ray casting for every family: the scene's BVH (core/bvh.h) in two SSBOs that
// glsl/common/raycast.glsl walks (closestHit, anyHit) from compute or fragment shaders.
//
//   RayCaster caster(scene);   // builds the BVH and uploads it
//   caster.bind();             // binds the SSBOs at SSBO_BVH_NODES, SSBO_BVH_TRIANGLES
//   program = Program::compute(..., caster.defines());   // or pass the same #defines to any shader
//
// A scene with alpha-masked materials: defines() gives ALPHA_MASK, and the walk then skips hits in the
// masks' holes (raycast.glsl), reading the frame's scene data, which must be bound too
// (Frame::bindSceneData, or GpuScene::bindGeometry and its materials at SSBO_MATERIALS).
//
// RayBatch casts a batch of rays and reads the hits back (tests, `bounce rays`).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/bvh.h"
#include "core/scene.h"
#include "gl/resource/buffer.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class RayCaster {
public:
    explicit RayCaster(const core::Scene& scene);

    void bind() const;
    // ALPHA_MASK for scenes with masked materials, else nothing.
    std::vector<Define> defines() const;
    bool hasAlphaMask() const { return hasAlphaMask_; }
    const core::Bvh& bvh() const { return bvh_; }
    std::size_t bytes() const { return nodes_.bytes() + triangles_.bytes(); }

private:
    core::Bvh bvh_;
    Buffer nodes_, triangles_;
    bool hasAlphaMask_ = false;
};

// What `rays` walks of raycast.glsl's closestHit cost, as per-scope work: the ray's set-up, and a walk
// estimated at twice the BVH's depth in boxes and two full leaves of triangles.
PassCost closestHitWork(const RayCaster& caster, double rays);

// std430 mirrors of glsl/frame/raycast_batch.glsl.
struct BatchRay {
    glm::vec3 origin;
    float tMin = 0.0f;
    glm::vec3 dir;
    float tMax = 0.0f;
};
struct BatchResult {
    std::uint32_t triangle; // global index, 0xFFFFFFFF without a closest hit
    float t;
    float b1, b2;          // barycentrics of v1 and v2
    std::uint32_t closest; // closestHit found a hit
    std::uint32_t any;     // anyHit found one
    std::uint32_t pad0, pad1;
};

enum class RayStage { Compute, Fragment };
inline constexpr int kQueryClosest = 1, kQueryAny = 2;

class RayBatch {
public:
    // defines: the caster's (RayCaster::defines()).
    explicit RayBatch(const std::vector<Define>& defines = {});
    // Uploads the rays and sizes the results (and, for the fragment stage, a viewport of up to
    // kFragmentWidth x ceil(n / kFragmentWidth) fragments).
    void upload(const std::vector<BatchRay>& rays);
    // Casts the uploaded rays (queries: kQueryClosest | kQueryAny) and waits for the GPU to finish.
    void cast(const RayCaster& caster, RayStage stage, int queries);
    std::vector<BatchResult> results() const;
    // upload + cast + results.
    std::vector<BatchResult> run(const RayCaster& caster, const std::vector<BatchRay>& rays, RayStage stage,
                                 int queries = kQueryClosest | kQueryAny);

    static constexpr int kFragmentWidth = 1024;

private:
    Program compute_, fragment_;
    VertexArray vao_;
    Buffer rays_, results_;
    Texture target_;
    Framebuffer framebuffer_;
    std::size_t count_ = 0;
    int width_ = 0, height_ = 0;
};

} // namespace bounce::gl
