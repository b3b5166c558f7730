// Scenes and helpers shared by the photon family's GL tests (tests/gl/photon_*_test.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/frame/frame.h"
#include "gl/frame/ray_caster.h"
#include "gl/resource/timer.h"
#include "gl/technique/photon/photon_tracer.h"
#include "gl/technique/photon/shading_clusters.h"
#include "tests/gl/closed_box.h"

namespace bounce::photontest {

// A closed box [0, s]^3, inward-facing, every surface Lambertian with albedo rho, a point light of
// intensity I at its centre; the camera inside, looking at a corner.
inline core::Scene closedBox(float rho, float size = 1.0f, glm::vec3 intensity = glm::vec3(1.0f))
{
    core::Scene s = testing::closedBox("closed box", rho, 0.0f, size);
    core::Light l;
    l.type = core::LightType::Point;
    l.position = glm::vec3(0.5f * size);
    l.intensity = intensity;
    s.lights.push_back(l);
    return s;
}

// The scene and its camera scaled by `k` (its lights are emissive triangles, scaled with the meshes).
inline core::Scene scaledScene(const core::Scene& scene, float k)
{
    core::Scene big = scene;
    for (core::Mesh& m : big.meshes)
        for (glm::vec3& p : m.positions) p *= k;
    big.camera.position *= k;
    big.camera.znear *= k;
    big.camera.zfar *= k;
    return big;
}

inline gl::FrameSettings smallFrame(int w, int h)
{
    gl::FrameSettings s;
    s.width = w;
    s.height = h;
    s.shadowMapSize = 256;
    return s;
}

// A scene's photons traced once on a small frame, with what traced them kept for the passes that read
// them next (a tree, a cut).
struct TracedPhotons {
    TracedPhotons(const core::Scene& scene, const gl::PhotonTracerSettings& settings)
        : frame(scene, smallFrame(8, 8)), counters("photon.counters", gl::kCounterSlots * 4), tracer(settings)
    {
        tracer.trace(frame, frame.rayCaster(), counters, timers);
    }
    gl::Frame frame;
    gl::Buffer counters;
    gl::PhotonTracer tracer;
    gl::PassTimers timers;
};

inline gl::PhotonTracerSettings photonPaths(int paths)
{
    gl::PhotonTracerSettings s;
    s.photons = paths;
    return s;
}

// A small frame's G-buffer and its shading clusters after one cluster() call, for the tests that look
// inside them.
struct ClusteredFrame {
    ClusteredFrame(const core::Scene& scene, int w, int h, int clusterCount)
        : frame(scene, smallFrame(w, h)),
          counters("photon.counters", gl::kCounterSlots * 4),
          clusters(settings(clusterCount))
    {
        frame.beginFrame();
        frame.renderGBuffer(timers);
        clusters.cluster(frame, glm::length(scene.bounds().extent()), counters, timers);
    }
    static gl::ShadingClusterSettings settings(int clusterCount)
    {
        gl::ShadingClusterSettings s;
        s.clusters = clusterCount;
        return s;
    }
    gl::Frame frame;
    gl::PassTimers timers;
    gl::Buffer counters;
    gl::ShadingClusters clusters;
};

} // namespace bounce::photontest
