// What the global ray-bundle tests share: scenes built in code (boxes, parallel squares, two rooms) and a
// harness that runs the family's passes direction by direction on one scene and reads the atlases back.
#pragma once

#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/frame/frame.h"
#include "gl/technique/grb/bundle_directions.h"
#include "gl/technique/grb/grb_atlas.h"
#include "gl/technique/grb/kbuffer.h"
#include "gl/technique/grb/radiance_atlases.h"
#include "tests/gl/closed_box.h"

namespace bounce::grbtest {

inline core::Material lambertian(float albedo, float emission = 0.0f)
{
    core::Material m;
    m.baseColor = glm::vec3(albedo);
    m.metallic = 0.0f;
    m.specular = 0.0f;
    m.emission = glm::vec3(emission);
    return m;
}

using testing::addQuad;

// An axis-aligned box [lo, hi], its faces towards the inside (or the outside), `skip` faces left out
// (bit i: face i of -y, +y, -x, +x, -z, +z).
inline core::Mesh box(glm::vec3 lo, glm::vec3 hi, bool inward, std::uint32_t material, unsigned skip = 0)
{
    core::Mesh m;
    m.material = material;
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    // Each face counter-clockwise seen from outside.
    const int f[6][4] = {{0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}, {0, 3, 2, 1}, {4, 5, 6, 7}};
    for (int i = 0; i < 6; ++i) {
        if (skip & (1u << i)) continue;
        if (inward)
            addQuad(m, c[f[i][3]], c[f[i][2]], c[f[i][1]], c[f[i][0]]);
        else
            addQuad(m, c[f[i][0]], c[f[i][1]], c[f[i][2]], c[f[i][3]]);
    }
    return m;
}

// The furnace: a closed unit box, every face albedo rho and emission Le, inward.
inline core::Scene furnace(float rho, float le, unsigned skip = 0)
{
    core::Scene s;
    s.name = "furnace";
    s.materials.push_back(lambertian(rho, le));
    s.meshes.push_back(box({0, 0, 0}, {1, 1, 1}, true, 0, skip));
    s.camera.position = {0.5f, 0.5f, 0.9f};
    s.camera.forward = glm::normalize(glm::vec3(-0.3f, -0.2f, -1.0f));
    s.camera.up = glm::normalize(glm::cross(glm::cross(s.camera.forward, glm::vec3(0, 1, 0)), s.camera.forward));
    s.camera.yfovRad = 1.2f;
    return s;
}

struct Texel {
    glm::vec3 position{0.0f}, normal{0.0f};
    int material = -1; // -1: empty
    glm::vec4 seed{0.0f}, direct{0.0f}, indirect{0.0f};
};

// The family's passes on one scene, direction by direction, with the atlases read back.
class Harness {
public:
    Harness(const core::Scene& scene, gl::KBufferSettings ks, float texelsPerMetre, bool interleaved = true)
        : scene_(scene), frame_(scene, frameSettings())
    {
        core::AtlasSettings as;
        as.texelsPerMetre = texelsPerMetre;
        atlas_ = std::make_unique<gl::GrbAtlas>(scene_, as);
        atlas_->fill(frame_, timers_);
        kbuffer_ = std::make_unique<gl::KBuffer>(ks);
        gl::RadianceSettings rs;
        rs.glossy = scene_.hasGlossy();
        rs.punctual = frame_.gpuScene().punctualLightCount() > 0;
        rs.interleaved = interleaved;
        radiance_ = std::make_unique<gl::RadianceAtlases>(*atlas_, *kbuffer_, rs);
        frame_.renderShadowMaps(timers_);
        radiance_->seed(frame_, *atlas_, timers_);
    }

    gl::BundleView view(glm::vec3 dir, glm::vec2 jitter = glm::vec2(0.5f)) const
    {
        return gl::bundleView(frame_.gpuScene().bounds(), dir, jitter, kbuffer_->size());
    }
    // One direction: capture and transfer.
    void direction(const gl::BundleView& v, glm::vec3 next = glm::vec3(0, 1, 0))
    {
        kbuffer_->capture(frame_, *atlas_, v, timers_);
        radiance_->transfer(frame_, *atlas_, *kbuffer_, v, next, timers_);
        timers_.endFrame(false);
    }
    // Directions first .. first + n - 1 of the Halton sequence.
    void directions(int n, int first = 0)
    {
        for (int i = first; i < first + n; ++i)
            direction(view(gl::bundleDirection(std::uint64_t(i)), gl::bundleJitter(std::uint64_t(i))),
                      gl::bundleDirection(std::uint64_t(i + 1)));
    }

    std::vector<Texel> texels() const
    {
        const std::vector<float> p = atlas_->position().readFloats(0, 4), n = atlas_->normal().readFloats(0, 4),
                                 s = radiance_->seedAtlas().readFloats(0, 4), d = radiance_->direct().readFloats(0, 4),
                                 i = radiance_->indirect().readFloats(0, 4);
        std::vector<Texel> out(p.size() / 4);
        for (std::size_t t = 0; t < out.size(); ++t) {
            Texel& x = out[t];
            x.position = {p[4 * t], p[4 * t + 1], p[4 * t + 2]};
            x.material = int(p[4 * t + 3]) - 1;
            x.normal = {n[4 * t], n[4 * t + 1], n[4 * t + 2]};
            x.seed = {s[4 * t], s[4 * t + 1], s[4 * t + 2], s[4 * t + 3]};
            x.direct = {d[4 * t], d[4 * t + 1], d[4 * t + 2], d[4 * t + 3]};
            x.indirect = {i[4 * t], i[4 * t + 1], i[4 * t + 2], i[4 * t + 3]};
        }
        return out;
    }

    gl::Frame& frame() { return frame_; }
    gl::GrbAtlas& atlas() { return *atlas_; }
    gl::KBuffer& kbuffer() { return *kbuffer_; }
    gl::RadianceAtlases& radiance() { return *radiance_; }
    gl::PassTimers& timers() { return timers_; }

private:
    static gl::FrameSettings frameSettings()
    {
        gl::FrameSettings f;
        f.width = f.height = 8;
        f.shadowMapSize = 256;
        return f;
    }
    core::Scene scene_;
    gl::Frame frame_;
    gl::PassTimers timers_;
    std::unique_ptr<gl::GrbAtlas> atlas_;
    std::unique_ptr<gl::KBuffer> kbuffer_;
    std::unique_ptr<gl::RadianceAtlases> radiance_;
};

inline gl::KBufferSettings kbufferSettings(gl::KBufferCapture c, int size, int k)
{
    gl::KBufferSettings s;
    s.capture = c;
    s.size = size;
    s.k = k;
    return s;
}

} // namespace bounce::grbtest
