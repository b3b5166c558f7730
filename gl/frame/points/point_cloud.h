// The shared lit point cloud of the point-based final gathers (micro-rendering, Ritschel et al. 2009;
// importance-driven point projection, Maletz, Wang & Bowers 2011): N points of the frame's surface sampler
// (core/surface_points.h, blue noise, each (triangle, barycentrics) with its area), in the median-split
// order of core/point_order.h (the leaves of micro-rendering's hierarchy and point projection's 512
// clusters at once), on the GPU (glsl/frame/points/point_cloud.glsl). Passes:
//   "point-update"  every point's position, normal and diffuse colour from (triangle, barycentrics) on the
//                   scene as it is now (point_update.comp)
//   "point-light"   direct light at every point by the frame's estimator, half floats (point_light.comp);
//                   in a scene with a glossy material, what each point's glossy lobe needs as well
//                   (point_cloud.glsl's `glossy`, compiled in with GLOSSY_POINTS)
//   "relight"       direct + the diffuse light gathered at the points' representatives (bounces > 1)
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/surface_points.h"
#include "gl/frame/frame.h"
#include "gl/frame/points/median_split.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

// std430 mirror of point_cloud.glsl's PointSample.
struct GpuPointSample {
    std::uint32_t triangle;
    float triangleShare;    // the point's area over its triangle's, at creation (the area follows deformation)
    glm::vec2 barycentrics; // scene.glsl's (b1, b2); after the share so that std430 packs it at offset 8
};

// The points of `scene`, `count` of them from the surface sampler with `seed`, in median-split order:
// computed once per (scene content, count, seed) and kept for the process (the sampler is the slow part,
// and tests and the bench make many renderers of one scene).
std::shared_ptr<const std::vector<core::SurfacePoint>> orderedSurfacePoints(const core::Scene& scene, std::size_t count,
                                                                            std::uint64_t seed);

// The surface point as the GPU reads it: core's (b0, b1) with p = b0 p0 + b1 p1 + (1 - b0 - b1) p2 become
// scene.glsl's (b1, b2) with p = (1 - b1 - b2) v0 + b1 v1 + b2 v2; its area becomes its share of its
// triangle's area (triangleAreaM2, > 0 where the sampler put a point).
GpuPointSample toGpuPointSample(const core::SurfacePoint& p, double triangleAreaM2);

class PointCloud {
public:
    // keepDirect: keep the direct light apart (multiple bounces add gathered light to it every frame).
    PointCloud(Frame& frame, std::size_t count, std::uint64_t seed, bool keepDirect);

    void update(Frame& frame, PassTimers& timers); // "point-update"
    // "recluster": puts the points back into the median-split order (core/point_order.h) of where they are
    // now, after update() (point projection re-clusters when the scene is manipulated, Maletz et al. §4),
    // then runs update() again so that the surfels follow; what else was per point (radiance, lobes) is
    // stale until light(). Gpu: on the GPU as the paper does it (MedianSplit). Cpu: the positions read back,
    // core::medianSplitOrder, the samples uploaded in the new order. The same order either way
    // (PointprojTest); Auto takes the CPU on a software rasteriser, where it was 5.5 times as fast for
    // 65,536 points (llvmpipe, 2 cores: 120 against 22 ms), and the GPU otherwise.
    enum class Recluster { Auto, Gpu, Cpu };
    void reorder(Frame& frame, PassTimers& timers, Recluster where = Recluster::Auto);
    void light(Frame& frame, PassTimers& timers); // "point-light"
    // "relight": radiance = direct + diffuse colour x gathered[i / stride] (vec4 per representative).
    void relight(const Buffer& gathered, int stride, PassTimers& timers);
    // Samples, surfels, radiance (and direct) at their SSBO slots.
    void bind() const;

    int count() const { return count_; }
    double totalAreaM2() const { return totalArea_; }
    // The radius of a point's disc, sqrt(area / pi), over the cloud (all points carry the same area at
    // creation; under deformation each point's area scales with its triangle's, and this stays).
    float discRadius() const { return discRadius_; }
    const Buffer& radiance() const { return radiance_; }
    // The scene has a glossy material: the points carry their glossy lobes (SSBO_POINT_GLOSSY), and every
    // program that reads the points is compiled with defines(), which says so (GLOSSY_POINTS).
    bool glossy() const { return glossy_; }
    const Buffer& glossyLobes() const { return glossyLobes_; } // uvec4 per point where glossy()
    std::vector<Define> defines() const;
    const Buffer& surfels() const { return surfels_; }

private:
    int count_ = 0;
    double totalArea_ = 0.0;
    float discRadius_ = 0.0f;
    bool keepDirect_ = false;
    bool glossy_ = false;
    int lightKinds_ = 0; // of the light program
    Buffer samples_, surfels_, radiance_, direct_, glossyLobes_;
    Buffer reordered_;                    // reorder()'s spare samples
    std::unique_ptr<MedianSplit> median_; // made by the first reorder()
    Program update_, light_, relight_;
    void makeLightProgram(const Frame& frame);
};

// The defines of glsl/frame/points/point_light.glsl: the frame's direct-light estimator in the moving frame's
// form in every frame (Frame::directLightDefines; point_light.glsl says why), with the frame's shadow rays
// (Frame::shadowRayDefines) where its lights are point, spot and directional lights alone; its uniforms are
// Frame::setDirectLightUniforms'.
std::vector<Define> pointLightDefines(const Frame& frame);
// Whether a program built with pointLightDefines for the frame's lights as they are now reads the frame's
// shadow maps: not where shadow rays light the points, nor in a scene without lights. What a technique
// whose points and hits are lit by them alone says in Technique::readsShadowMaps.
bool pointLightReadsShadowMaps(const Frame& frame);
// The kinds of light a scene has as bits (1: punctual, 2: area): a program built with pointLightDefines is
// built again where they change (Frame::setLights, an area light flattened by Frame::moveVertices).
int lightKinds(const GpuScene& scene);
// What hit_radiance.glsl's hitDirectRadiance costs for `hits` hits, as per-scope work: the hit's normal and
// material, and the lights at it as the direct pass counts them.
PassCost hitRadianceWork(const Frame& frame, double hits);

} // namespace bounce::gl
