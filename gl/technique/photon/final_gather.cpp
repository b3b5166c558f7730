#include "gl/technique/photon/final_gather.h"

#include <algorithm>
#include <bit>
#include <string>
#include <vector>

#include "gl/context/context.h"
#include "gl/frame/bindings.h"
#include "gl/frame/shader_costs.h"
#include "gl/gl.h"
#include "gl/probe/machine_probe.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/pass_state.h"
#include "gl/technique/photon/bindings.h"
#include "gl/technique/photon/photon_tracer.h"

namespace bounce::gl {

namespace {

// The density it gathers from; the hits' direct light is the frame's (DirectLitProgram adds its defines).
std::vector<Define> gatherDefines(const Frame& frame, const FinalGatherSettings& s)
{
    // Gather rays pass through the holes of alpha masks (raycast.glsl, ALPHA_MASK).
    const GpuScene& scene = frame.gpuScene();
    std::vector<Define> d = scene.alphaMaskDefines();
    // No glossy terms at the hits (common/brdf.glsl) where the scene has no lobe.
    if (!frame.scene().hasGlossy()) d.push_back({"SCENE_DIFFUSE_ONLY", "1"});
    if (s.causticAlpha > 0.0f) d.push_back({"CAUSTIC_MAP", "1"});
    if (s.fullPhotonMap) {
        d.push_back({"DENSITY_PHOTONS", "1"});
        d.push_back({"NEAREST_K", std::to_string(s.densityPhotons)});
    } else if (s.cutGrid) {
        d.push_back({"CUT_GRID", "1"});
    }
    return d;
}

constexpr int kGatherGroup = 256; // photon_gather.comp's GATHER_GROUP: one work group per cluster

std::vector<Define> interpolationDefines(bool glossySampled)
{
    if (glossySampled) return {{"GLOSSY_SAMPLED", "1"}};
    return {};
}

// The work of `rays` gather rays (photon_gather.glsl), each taken to hit (a bound), `extraLookups` of them
// looked up again at twice the radius.
PassCost gatherRayWork(const Frame& frame, const RayCaster& caster, const PhotonTree& tree, const IlluminationCut& cut,
                       const FinalGatherSettings& settings, double rays, double extraLookups)
{
    // Per ray: its direction, a BVH walk, then photon_gather.glsl reads the triangle's indices, vertices and
    // material (152 bytes; a bilinear base-colour sample where the scene has textures), its direct light from
    // every light (directLightsCost), the irradiance there, the BRDF.
    const double punctual = frame.gpuScene().punctualLightCount(), area = frame.lights().count() - punctual;
    const PassCost lights = directLightsCost(frame, punctual, area);
    PassCost w = bvhWalkWork(caster.bvh(), rays);
    w.flopsFixed += rays * (215 + lights.flops);
    w.fetchesFixed = rays * ((frame.gpuScene().hasTextures() ? 4 : 0) + lights.fetches);
    w.bytesFixed += rays * (152 + lights.bytesRead);
    w.uniformWordsFixed = rays * lights.uniformWords;
    if (settings.fullPhotonMap) {
        const PassCost density = nearestPhotonsWork(tree, settings.densityPhotons, rays);
        w.flopsFixed += density.flopsFixed;
        w.bytesFixed += density.bytesFixed;
        return w;
    }
    // cut_lookup.glsl per hit: the walk taken as 2 x log2(cut size) nodes visited, each its box, flags and,
    // in the cut, its kernel (64 bytes, 20 flops; an estimate: the walk's length is known only on the GPU);
    // the grid's list taken as twice the mean list (cells on surfaces hold more than empty space), a kernel
    // each. Again by the walk at twice the radius for the hits no kernel reached.
    const double walk = 2.0 * std::max(double(std::bit_width(cut.size())), 1.0);
    const glm::ivec3 d = cut.gridDims();
    const double cells = double(d.x) * d.y * d.z;
    const double list = settings.cutGrid && cells > 0 ? 2.0 * cut.gridEntries() / cells : walk;
    const double visits = rays * list + extraLookups * walk;
    w.flopsFixed += visits * 20;
    w.bytesFixed += visits * 64;
    return w;
}

// Whether a surface of the scene has a lobe no rougher than causticRoughness (0: none counts).
bool hasNearSpecular(const core::Scene& scene, float causticRoughness)
{
    for (const core::Mesh& m : scene.meshes)
        if (m.material < scene.materials.size()) {
            const core::Material& mat = scene.materials[m.material];
            if (mat.isGlossy() && causticRoughness > 0.0f && mat.roughness <= causticRoughness) return true;
        }
    return false;
}

} // namespace

FinalGather::FinalGather(const Frame& frame, const FinalGatherSettings& settings)
    : settings_(settings),
      program_("photon.gather", "technique/photon/photon_gather.comp", gatherDefines(frame, settings))
{}

void FinalGather::gather(const Frame& frame, const RayCaster& caster, const PhotonTree& tree, const Buffer& photons,
                         const IlluminationCut& cut, const ShadingClusters& clusters, float sceneSize, Buffer& counters,
                         PassTimers& timers)
{
    // photon_gather.comp per invocation (256 per cluster): its cluster read, the rays' rotation hashed, the
    // group's sums reduced in shared memory (8 steps); its rays are added below.
    PassCost cost;
    cost.flops = 70;
    cost.bytesRead = sizeof(GpuCluster);
    auto t = timers.scope("gather", cost);
    t.expectComputes(rowsInvocations(clusters.count(), kGatherGroup)); // a group per cluster
    const std::uint32_t zero[2] = {0, 0};
    counters.update((kCounterFirst + 1) * 4, sizeof zero, zero);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (clusters.count() == 0) {
        fallback_ = uncovered_ = 0;
        return;
    }
    // The hits' direct light as the frame's pixels get it, in this frame's form (still frames: the emitters
    // sampled at the frame's point; moving: the frame's PCF), its uniforms set.
    Program& program = program_.forFrame(frame);
    frame.bindSceneData();
    caster.bind();
    tree.bind(program);
    photons.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTONS);
    cut.bindLookup(program);
    clusters.bind();
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
    program.set("clusterCount", clusters.count());
    program.set("gatherRays", unsigned(std::max(settings_.rays, 1)));
    program.set("rayEpsilon", 1e-5f * sceneSize);
    program.set("minDistance", 1e-4f * sceneSize);
    program.set("maxDistance", sceneSize);
    // New rays in every still frame: the gather's noise averages out over the frames.
    program.set("seed", frame.sampler().hashSeed(settings_.seed));
    program.set("causticAlpha", settings_.causticAlpha);
    // In rows: one group per cluster, and gathering at every pixel makes a cluster of each (65,536 at 256^2,
    // past the 65,535 groups a driver may allow on one axis).
    dispatchRows(program, clusters.count(), kGatherGroup);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t hits[2] = {0, 0};
    counters.download((kCounterFirst + 1) * 4, sizeof hits, hits);
    fallback_ = hits[0];
    uncovered_ = hits[1];
    t.addWork(gatherRayWork(frame, caster, tree, cut, settings_,
                            double(clusters.nonEmpty()) * std::max(settings_.rays, 1),
                            double(fallback_) + double(uncovered_)));
}

GlossyGather::GlossyGather(const Frame& frame, int rays, bool cutGrid)
    : rays_(frame.scene().hasGlossy() ? std::max(rays, 0) : 0), cutGrid_(cutGrid)
{
    if (rays_ == 0) return;
    FinalGatherSettings s;
    s.cutGrid = cutGrid_;
    std::vector<Define> d = gatherDefines(frame, s);
    const std::vector<Define> g = frame.gbufferDefines();
    d.insert(d.end(), g.begin(), g.end());
    program_ = DirectLitProgram("photon.glossy", "technique/photon/photon_glossy.comp", d);
}

void GlossyGather::run(Frame& frame, const RayCaster& caster, const PhotonTree& tree, const Buffer& photons,
                       const IlluminationCut& cut, float sceneSize, PassTimers& timers)
{
    // photon_glossy.comp per pixel and ray: its surface and BRDF read, the lobe's basis and sample, the
    // weight, the target read and written; the ray's own work as a final-gather ray's (a bound: every pixel
    // taken to have a lobe and its ray to hit).
    PassCost cost;
    cost.flops = 150;
    cost.fetches = 3;
    cost.bytesRead = 8 + 2 * 8 + 16;
    cost.bytesWritten = 16;
    auto t = timers.scope("glossy", cost); // timed in every scene, as every declared pass: empty without a lobe
    t.expectComputes(rays_ == 0 ? 0.0 : rays_ * computeInvocations({frame.width(), frame.height(), 1}, {8, 8, 1}));
    if (rays_ == 0) return;
    FinalGatherSettings s;
    s.cutGrid = cutGrid_;
    t.addWork(gatherRayWork(frame, caster, tree, cut, s, double(frame.width()) * frame.height() * rays_, 0.0));
    Program& program = program_.forFrame(frame);
    frame.bindGBuffer();
    frame.bindSceneData();
    caster.bind();
    tree.bind(program);
    photons.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTONS);
    cut.bindLookup(program);
    program.set("viewport", glm::ivec2(frame.width(), frame.height()));
    program.set("cameraPosition", frame.camera().position);
    program.set("rayCount", unsigned(rays_));
    // The still index in still frames; in a moving frame 0, or a new seed each frame under temporal reuse.
    const FrameSampler& sampler = frame.sampler();
    program.set("seed", sampler.stillIndex() > 0 ? std::uint32_t(sampler.stillIndex()) : sampler.hashSeed(0));
    program.set("rayEpsilon", 1e-5f * sceneSize);
    frame.indirect().bindImage(0, GL_READ_WRITE);
    for (int j = 0; j < rays_; ++j) {
        program.set("rayIndex", unsigned(j));
        dispatchCompute(program, {frame.width(), frame.height(), 1}, {8, 8, 1});
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

CausticMap::CausticMap(const Frame& frame, float causticRoughness, float radius)
    : active_(hasNearSpecular(frame.scene(), causticRoughness)), roughness_(causticRoughness), radius_(radius)
{
    if (active_)
        program_ = Program::compute("photon.caustic", "technique/photon/photon_caustic.comp", frame.gbufferDefines());
}

void CausticMap::run(Frame& frame, const PhotonTree& tree, const Buffer& photons, float sceneSize, PassTimers& timers)
{
    // photon_caustic.comp per pixel: its surface and BRDF read, the tree's walk within the radius (taken as
    // two nodes per level, an estimate: its length is known only on the GPU), the target read and written.
    PassCost cost;
    cost.flops = 60 + 2 * 20 * double(std::max(tree.depth(), 1));
    cost.fetches = 3;
    cost.bytesRead = 8 + 2 * 8 + 16 + 2 * 32 * double(std::max(tree.depth(), 1));
    cost.bytesWritten = 16;
    auto t = timers.scope("caustic", cost); // timed in every scene: empty without a near-specular lobe
    t.expectComputes(active_ ? computeInvocations({frame.width(), frame.height(), 1}, {8, 8, 1}) : 0.0);
    if (!active_) return;
    frame.bindGBuffer();
    tree.bind(program_);
    photons.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTONS);
    program_.set("viewport", glm::ivec2(frame.width(), frame.height()));
    program_.set("cameraPosition", frame.camera().position);
    program_.set("radius", radius_ * sceneSize);
    frame.indirect().bindImage(0, GL_READ_WRITE);
    dispatchCompute(program_, {frame.width(), frame.height(), 1}, {8, 8, 1});
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

Interpolation::Interpolation(bool asCompute, bool glossySampled)
    : asCompute_(asCompute),
      program_(asCompute
                   ? Program::compute("photon.interpolate", "technique/photon/photon_interpolate.comp",
                                      interpolationDefines(glossySampled))
                   : Program::graphics("photon.interpolate", "frame/fullscreen.vert",
                                       "technique/photon/photon_interpolate.frag", interpolationDefines(glossySampled)))
{} // the fragment form's framebuffer is made in run(), on the frame's indirect texture; the compute form has none

bool Interpolation::defaultAsCompute()
{
    return !preferFragmentPasses();
}

void Interpolation::run(Frame& frame, const ShadingClusters& clusters, float maxError, bool ownSampleOnly,
                        PassTimers& timers, bool writeIrradiance)
{
    // photon_interpolate.comp or .frag per pixel: its surface, cluster index, own cluster, diffuse and
    // specular texels read, Ward's weight to its own sample, the split-sum albedo, its radiance written.
    PassCost cost;
    cost.flops = 120;
    cost.fetches = 3;
    cost.bytesRead = 8 + 4 + sizeof(GpuCluster) + 2 * 8;
    cost.bytesWritten = 16;
    auto t = timers.scope("interpolate", cost);
    if (asCompute_)
        t.expectComputes(computeInvocations({frame.width(), frame.height(), 1}, {8, 8, 1}));
    else
        t.expectFragments(frame.width(), frame.height());
    if (!ownSampleOnly) {
        // The walk of the tree of samples per pixel (a bound: every pixel has geometry), taken as two nodes
        // per level, a box test each above the leaves and a sample's weight at them (an estimate: the walk's
        // length is known only on the GPU).
        const double pixels = double(frame.width()) * frame.height(), boxes = 2.0 * clusters.pointTreeDepth();
        PassCost walk;
        walk.flopsFixed = pixels * (20 * boxes + 2 * 30);
        walk.bytesFixed = pixels * (sizeof(GpuPointNode) * boxes + 2 * (sizeof(GpuPointNode) + sizeof(GpuCluster)));
        t.addWork(walk);
    }
    if (!asCompute_ && attached_ != frame.indirect().id()) {
        framebuffer_ = Framebuffer("photon.interpolate");
        framebuffer_.attach(GL_COLOR_ATTACHMENT0, frame.indirect());
        framebuffer_.checkComplete();
        attached_ = frame.indirect().id();
    }
    if (!asCompute_) PassState::fullscreen(framebuffer_, frame.width(), frame.height()).apply();
    frame.bindGBuffer();
    clusters.bind();
    clusters.bindPointTree(program_);
    clusters.clusterOfPixel().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_OF_PIXEL);
    program_.set("viewport", glm::ivec2(frame.width(), frame.height()));
    program_.set("clusterCount", clusters.count());
    program_.set("maxError", maxError);
    program_.set("ownSampleOnly", ownSampleOnly ? 1 : 0);
    program_.set("writeIrradiance", writeIrradiance ? 1 : 0);
    program_.set("cameraPosition", frame.camera().position);
    if (asCompute_) {
        frame.indirect().bindImage(0, GL_WRITE_ONLY);
        dispatchCompute(program_, {frame.width(), frame.height(), 1}, {8, 8, 1});
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        return;
    }
    program_.use();
    frame.drawFullscreen();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace bounce::gl
