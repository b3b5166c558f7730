#include "ref/embree_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace bounce::ref {

namespace {

void throwOnDeviceError(RTCDevice device, const char* what)
{
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree: ") + what + " failed (error " + std::to_string(int(e)) + ")");
}

float srgbToLinear(float c)
{
    // IEC 61966-2-1.
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// The context of an all-hits query: Embree hands the filter its RTCIntersectContext pointer, so the
// context is the first member and the collector follows it.
struct CollectContext {
    RTCIntersectContext context;
    std::vector<Hit>* out;
};

void collectFilter(const RTCFilterFunctionNArguments* args)
{
    // Single rays only (rtcIntersect1), so N == 1.
    auto* ctx = reinterpret_cast<CollectContext*>(args->context);
    const auto* hit = reinterpret_cast<const RTCHit*>(args->hit);
    args->valid[0] = 0; // reject: traversal goes on and reports every other candidate
    // With spatial splits (high build quality) one triangle may be reported more than once.
    for (const Hit& h : *ctx->out)
        if (h.mesh == hit->geomID && h.prim == hit->primID) return;
    Hit h;
    h.mesh = hit->geomID;
    h.prim = hit->primID;
    h.u = hit->u;
    h.v = hit->v;
    ctx->out->push_back(h);
}

// Geometry filter of alpha-masked meshes (closest hit and occlusion): a candidate hit in a hole of the
// mask is rejected and traversal goes on, as if the triangle were not there.
void alphaMaskFilter(const RTCFilterFunctionNArguments* args)
{
    const auto* scene = static_cast<const EmbreeScene*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        if (scene->cutOut(RTCHitN_geomID(args->hit, args->N, i), RTCHitN_primID(args->hit, args->N, i),
                          RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)))
            args->valid[i] = 0;
    }
}

RTCRayHit makeRayHit(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax)
{
    RTCRayHit rh;
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = tmin;
    rh.ray.tfar = tmax;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

} // namespace

EmbreeScene::EmbreeScene(const core::Scene& scene, bool withAllHits)
    : scene_(scene), masks_(scene), withAllHits_(withAllHits)
{
    if (const std::string err = scene.validate(); !err.empty()) throw std::invalid_argument("invalid scene: " + err);

    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("Embree: cannot create a device");
    rtcScene_ = rtcNewScene(device_);
    // Context filters are needed by allHits() only.
    if (withAllHits) rtcSetSceneFlags(rtcScene_, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    rtcSetSceneBuildQuality(rtcScene_, RTC_BUILD_QUALITY_HIGH);

    triangleOffset_.assign(scene.meshes.size() + 1, 0);
    const bool normalMaps = scene.hasNormalMaps();
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const core::Mesh& mesh = scene.meshes[m];
        const std::size_t triCount = mesh.indices.size() / 3;
        triangleOffset_[m + 1] = triangleOffset_[m] + std::uint32_t(triCount);
        for (std::size_t t = 0; t < triCount; ++t) {
            const std::uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1], i2 = mesh.indices[3 * t + 2];
            TriangleRecord r;
            r.p0 = mesh.positions[i0];
            r.p1 = mesh.positions[i1];
            r.p2 = mesh.positions[i2];
            const glm::vec3 cross = glm::cross(r.p1 - r.p0, r.p2 - r.p0);
            const float len = glm::length(cross);
            r.ng = len > 0.0f ? cross / len : glm::vec3(0.0f, 0.0f, 1.0f);
            r.n0 = mesh.normals[i0];
            r.n1 = mesh.normals[i1];
            r.n2 = mesh.normals[i2];
            const bool uvs = !mesh.uvs.empty();
            r.uv0 = uvs ? mesh.uvs[i0] : glm::vec2(0.0f);
            r.uv1 = uvs ? mesh.uvs[i1] : glm::vec2(0.0f);
            r.uv2 = uvs ? mesh.uvs[i2] : glm::vec2(0.0f);
            r.mesh = std::uint32_t(m);
            triangles_.push_back(r);
            if (normalMaps) {
                TangentRecord tr;
                if (!mesh.tangents.empty() && uvs) {
                    tr.t0 = mesh.tangents[i0];
                    tr.t1 = mesh.tangents[i1];
                    tr.t2 = mesh.tangents[i2];
                }
                tangents_.push_back(tr);
            }
        }
        if (triCount == 0) continue;
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        // Embree allocates these with the padding its SIMD loads need past the last vertex.
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                     3 * sizeof(float), mesh.positions.size()));
        auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), triCount));
        if (!vertices || !indices) throwOnDeviceError(device_, "geometry buffer allocation");
        std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
        std::memcpy(indices, mesh.indices.data(), triCount * 3 * sizeof(std::uint32_t));
        if (scene.materials[mesh.material].isMasked()) {
            rtcSetGeometryUserData(geom, this);
            rtcSetGeometryIntersectFilterFunction(geom, alphaMaskFilter);
            rtcSetGeometryOccludedFilterFunction(geom, alphaMaskFilter);
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(rtcScene_, geom, unsigned(m));
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(rtcScene_);
    throwOnDeviceError(device_, "scene build");

    textures_.resize(scene.textures.size());
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const core::Texture& t = scene.textures[i];
        LinearTexture& lt = textures_[i];
        if (t.width <= 0 || t.height <= 0 || t.rgba8.size() < std::size_t(t.width) * std::size_t(t.height) * 4)
            continue;
        float lut[256];
        for (int c = 0; c < 256; ++c) lut[c] = srgbToLinear(float(c) / 255.0f);
        lt.width = t.width;
        lt.height = t.height;
        lt.texels.resize(std::size_t(t.width) * std::size_t(t.height));
        for (std::size_t p = 0; p < lt.texels.size(); ++p)
            lt.texels[p] = {lut[t.rgba8[4 * p]], lut[t.rgba8[4 * p + 1]], lut[t.rgba8[4 * p + 2]]};
    }
    // Normal maps keep their bytes' linear values (v / 255), as the GPU's RGBA8 array does.
    if (normalMaps) {
        normalTextures_.resize(scene.textures.size());
        for (const core::Material& m : scene.materials) {
            if (!m.hasNormalMap() || std::size_t(m.normalTexture) >= scene.textures.size()) continue;
            const core::Texture& t = scene.textures[std::size_t(m.normalTexture)];
            LinearTexture& lt = normalTextures_[std::size_t(m.normalTexture)];
            if (!lt.texels.empty() || t.width <= 0 || t.height <= 0 ||
                t.rgba8.size() < std::size_t(t.width) * std::size_t(t.height) * 4)
                continue;
            lt.width = t.width;
            lt.height = t.height;
            lt.texels.resize(std::size_t(t.width) * std::size_t(t.height));
            for (std::size_t p = 0; p < lt.texels.size(); ++p)
                lt.texels[p] = glm::vec3(t.rgba8[4 * p], t.rgba8[4 * p + 1], t.rgba8[4 * p + 2]) / 255.0f;
        }
    }
}

EmbreeScene::~EmbreeScene()
{
    if (rtcScene_) rtcReleaseScene(rtcScene_);
    if (device_) rtcReleaseDevice(device_);
}

bool EmbreeScene::intersect(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax, Hit& hit,
                            std::uint64_t& rays) const
{
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = makeRayHit(o, d, tmin, tmax);
    rtcIntersect1(rtcScene_, &context, &rh);
    ++rays;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit.t = rh.ray.tfar;
    hit.mesh = rh.hit.geomID;
    hit.prim = rh.hit.primID;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    return true;
}

bool EmbreeScene::occluded(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax, std::uint64_t& rays) const
{
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = makeRayHit(o, d, tmin, tmax).ray;
    rtcOccluded1(rtcScene_, &context, &ray);
    ++rays;
    return ray.tfar < 0.0f; // Embree sets tfar to -inf when something blocks the ray
}

void EmbreeScene::allHits(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax, std::vector<Hit>& out,
                          std::uint64_t& rays) const
{
    out.clear();
    if (!withAllHits_) throw std::logic_error("EmbreeScene::allHits needs a scene built withAllHits");
    CollectContext ctx;
    rtcInitIntersectContext(&ctx.context);
    ctx.context.filter = collectFilter;
    ctx.out = &out;
    RTCRayHit rh = makeRayHit(o, d, tmin, tmax);
    rtcIntersect1(rtcScene_, &ctx.context, &rh);
    ++rays;
    // The distance from the barycentrics (what the filter sees of tfar is not specified for rejected hits).
    const float invLen2 = 1.0f / glm::dot(d, d);
    for (Hit& h : out) h.t = glm::dot(surface(h).p - o, d) * invLen2;
}

void EmbreeScene::triangle(std::uint32_t global, glm::vec3& p0, glm::vec3& p1, glm::vec3& p2, std::uint32_t& mesh) const
{
    const TriangleRecord& r = triangles_[global];
    mesh = r.mesh;
    p0 = r.p0;
    p1 = r.p1;
    p2 = r.p2;
}

SurfacePoint EmbreeScene::surface(const Hit& hit) const
{
    const std::uint32_t global = globalTriangle(hit.mesh, hit.prim);
    const TriangleRecord& r = triangles_[global];
    const float w = 1.0f - hit.u - hit.v;
    SurfacePoint s;
    // The point from the barycentrics rather than o + t d: it lies on the triangle to float precision.
    s.p = w * r.p0 + hit.u * r.p1 + hit.v * r.p2;
    s.ng = r.ng;
    const glm::vec3 n = w * r.n0 + hit.u * r.n1 + hit.v * r.n2;
    const float nlen2 = glm::dot(n, n);
    s.ns = nlen2 > 0.0f ? n / std::sqrt(nlen2) : s.ng;
    if (glm::dot(s.ns, s.ng) < 0.0f) s.ns = -s.ns; // normals that disagree with the winding: winding wins
    s.uv = w * r.uv0 + hit.u * r.uv1 + hit.v * r.uv2;
    s.triangle = global;
    s.material = &scene_.materials[scene_.meshes[r.mesh].material];
    if (!tangents_.empty() && s.material->hasNormalMap()) {
        const TangentRecord& t = tangents_[global];
        s.ns = normalMapped(s.ns, w * t.t0 + hit.u * t.t1 + hit.v * t.t2, *s.material, s.uv);
    }
    return s;
}

glm::vec3 EmbreeScene::normalMapped(const glm::vec3& n, const glm::vec4& tangent, const core::Material& m,
                                    const glm::vec2& uv) const
{
    if (std::size_t(m.normalTexture) >= normalTextures_.size()) return n;
    const LinearTexture& map = normalTextures_[std::size_t(m.normalTexture)];
    if (map.texels.empty()) return n;
    glm::vec3 t = glm::vec3(tangent) - n * glm::dot(n, glm::vec3(tangent));
    const float t2 = glm::dot(t, t);
    if (!(t2 > 1e-12f)) return n; // no tangent (a mesh without), or one along n
    t /= std::sqrt(t2);
    const glm::vec3 b = glm::cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
    glm::vec3 v = core::bilinearRepeat(map.texels, map.width, map.height, uv) * 2.0f - 1.0f;
    v.x *= m.normalScale;
    v.y *= m.normalScale;
    const glm::vec3 bent = v.x * t + v.y * b + v.z * n;
    const float len2 = glm::dot(bent, bent);
    return len2 > 1e-12f ? bent / std::sqrt(len2) : n;
}

glm::vec3 EmbreeScene::textureColor(const core::Material& m, const glm::vec2& uv) const
{
    if (m.baseColorTexture < 0 || std::size_t(m.baseColorTexture) >= textures_.size()) return glm::vec3(1.0f);
    const LinearTexture& t = textures_[std::size_t(m.baseColorTexture)];
    if (t.texels.empty()) return glm::vec3(1.0f);
    return core::bilinearRepeat(t.texels, t.width, t.height, uv);
}

float EmbreeScene::textureAlpha(const core::Material& m, const glm::vec2& uv) const
{
    return masks_.alpha(m, uv);
}

bool EmbreeScene::cutOut(std::uint32_t mesh, std::uint32_t prim, float u, float v) const
{
    const core::Material& m = scene_.materials[scene_.meshes[mesh].material];
    if (!m.isMasked()) return false;
    const TriangleRecord& r = triangles_[globalTriangle(mesh, prim)];
    const glm::vec2 uv = (1.0f - u - v) * r.uv0 + u * r.uv1 + v * r.uv2;
    return m.cutsOut(textureAlpha(m, uv));
}

float EmbreeScene::offsetScale(const glm::vec3& p)
{
    const float m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1.0f});
    return 1e-5f * m;
}

} // namespace bounce::ref
