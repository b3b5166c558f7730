#include "gl/frame/rsm.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gl/frame/bindings.h"
#include "gl/frame/light_views.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

namespace {

struct GpuRsmView {
    glm::mat4 viewProj;
    glm::vec4 originOrtho;
    glm::vec4 directionTexel;
};

// The integral of the solid angle over [0, x] x [0, y] of the image plane at distance 1.
double cornerSolidAngle(double x, double y)
{
    return std::atan2(x * y, std::sqrt(1.0 + x * x + y * y));
}

} // namespace

std::vector<ParamDecl> rsmParams()
{
    return {
        {"rsmSize", ParamType::Int, 256, 4, 2048,
         "RSM texels per side of each light view (the paper: 256); an RSM pyramid or VPL tree needs a power of two"},
        {"exactSolidAngle", ParamType::Bool, 0, 0, 1,
         "exact solid angle of each RSM texel instead of Eq. 4's equal share (slightly slower RSM pass)"},
    };
}

RsmSettings rsmSettingsFrom(const ParamValues& values)
{
    RsmSettings s;
    s.size = values.getInt("rsmSize");
    s.exactSolidAngle = values.getBool("exactSolidAngle");
    return s;
}

void requireRsmSize(const std::string& technique, int size, bool powerOfTwo, int maxSize)
{
    if (powerOfTwo && (size < 1 || !std::has_single_bit(unsigned(size))))
        throw std::invalid_argument(technique + ": rsmSize must be a power of two, not " + std::to_string(size));
    if (size > maxSize)
        throw std::invalid_argument(technique + ": rsmSize must be at most " + std::to_string(maxSize) + ", not " +
                                    std::to_string(size));
}

double RsmPass::equalTexelSolidAngle(double fovRad, int size)
{
    const double s = std::sin(0.5 * fovRad);
    return 4.0 * std::asin(s * s) / (double(size) * double(size)); // Eq. 4, in steradians
}

double RsmPass::exactTexelSolidAngle(double fovRad, int size, int x, int y)
{
    const double t = std::tan(0.5 * fovRad);
    const double x0 = t * (-1.0 + 2.0 * x / size), x1 = t * (-1.0 + 2.0 * (x + 1) / size);
    const double y0 = t * (-1.0 + 2.0 * y / size), y1 = t * (-1.0 + 2.0 * (y + 1) / size);
    return cornerSolidAngle(x1, y1) - cornerSolidAngle(x0, y1) - cornerSolidAngle(x1, y0) + cornerSolidAngle(x0, y0);
}

RsmPass::RsmPass(const RsmSettings& settings)
    : settings_(settings), fbo_("rsm.fbo"), program_("rsm", "frame/rsm.vert", "frame/rsm.frag")
{
    if (settings_.size < 1) throw std::invalid_argument("RSM size must be at least 1");
    if (settings_.levels > 0) {
        if (!std::has_single_bit(unsigned(settings_.size)))
            throw std::invalid_argument("rsmSize must be a power of two for the RSM pyramid, not " +
                                        std::to_string(settings_.size));
        if (settings_.levels > int(std::bit_width(unsigned(settings_.size))) - 1)
            throw std::invalid_argument("the RSM pyramid of a " + std::to_string(settings_.size) +
                                        "^2 RSM has at most " +
                                        std::to_string(std::bit_width(unsigned(settings_.size)) - 1) + " levels");
        reduce_ = Program::compute("rsm.reduce", "frame/rsm_reduce.comp");
    }
}

void RsmPass::buildViews(const Frame& frame)
{
    // The spot's view covers exactly its cone: Eq. 4 shares the frustum's solid angle among the texels.
    LightViewOptions options;
    options.fovMargin = 1.0f;
    views_ = buildLightViews(frame.gpuScene().lights(), frame.gpuScene().bounds(), options).views;
}

void RsmPass::allocate(int layers)
{
    const int size = settings_.size;
    const int width = settings_.levels > 0 ? size + size / 2 : size;
    position_ = Texture::create2DArray("rsm.position", GL_RGBA32F, width, size, layers);
    normal_ = Texture::create2DArray("rsm.normal", GL_RGBA32F, width, size, layers);
    flux_ = Texture::create2DArray("rsm.flux", GL_RGBA32F, width, size, layers);
    if (settings_.levels > 0) {
        depthRange_ = Texture::create2DArray("rsm.depthRange", GL_RG32F, width, size, layers);
        normalMin_ = Texture::create2DArray("rsm.normalMin", GL_RGBA16F, width, size, layers);
        normalMax_ = Texture::create2DArray("rsm.normalMax", GL_RGBA16F, width, size, layers);
    }
    if (!depth_) depth_ = Texture::create2D("rsm.depth", GL_DEPTH_COMPONENT32F, size, size);
    const float zero[4] = {0, 0, 0, 0};
    position_.clear(0, zero);
    normal_.clear(0, zero);
    flux_.clear(0, zero);
    solidAngleFovs_.clear();
    solidAngles_ = Texture();
}

void RsmPass::updateSolidAngles()
{
    if (!settings_.exactSolidAngle) return;
    std::vector<float> fovs;
    for (const LightView& v : views_) fovs.push_back(v.orthographic ? 0.0f : v.fovRad);
    if (fovs.empty() || fovs == solidAngleFovs_) return;
    const int size = settings_.size;
    if (!solidAngles_ || solidAngles_.layers() != int(fovs.size()))
        solidAngles_ = Texture::create2DArray("rsm.texelSolidAngles", GL_R32F, size, size, int(fovs.size()));
    std::vector<float> table(std::size_t(size) * std::size_t(size));
    for (std::size_t layer = 0; layer < fovs.size(); ++layer) {
        // In double: a texel's solid angle is a small difference of O(1) corner integrals.
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                table[std::size_t(y) * size + x] =
                    fovs[layer] > 0.0f ? float(exactTexelSolidAngle(fovs[layer], size, x, y)) : 0.0f;
        glTextureSubImage3D(solidAngles_.id(), 0, 0, 0, GLint(layer), size, size, 1, GL_RED, GL_FLOAT, table.data());
    }
    solidAngleFovs_ = fovs;
}

void RsmPass::render(Frame& frame, PassTimers& timers)
{
    {
        // rsm.frag per fragment: the material, the light's flux through the texel, three RGBA32F targets
        // (and the pyramid's level 0 of depth range and normal bounds), depth; the scene once per view.
        const bool pyramid = settings_.levels > 0;
        PassCost cost;
        cost.flops = 60;
        cost.fetches = frame.gpuScene().hasTextures() ? 4 : 0;
        cost.bytesRead = 4;
        cost.bytesWritten = 3 * 16 + 4 + (pyramid ? 8 + 2 * 8 : 0);
        auto t = timers.scope("rsm", cost);
        buildViews(frame);
        PassCost geometry;
        geometry.triangles = double(views_.size()) * double(frame.gpuScene().triangleCount());
        t.addWork(geometry);
        const int layers = std::max(1, viewCount());
        if (!position_ || position_.layers() != layers) allocate(layers);
        std::vector<GpuRsmView> gv;
        for (const LightView& v : views_)
            gv.push_back({v.proj * v.view, glm::vec4(v.origin, v.orthographic ? 1.0f : 0.0f),
                          glm::vec4(v.direction, texelSide(v))});
        if (gv.empty()) gv.push_back({});
        if (!viewsBuffer_ || viewsBuffer_.bytes() != gv.size() * sizeof(GpuRsmView))
            viewsBuffer_ = Buffer::fromVector("rsm.views", gv);
        else
            viewsBuffer_.update(0, gv.size() * sizeof(GpuRsmView), gv.data());
        updateSolidAngles();
        renderViews(frame);
    }
    if (settings_.levels > 0 && !views_.empty()) {
        PassCost cost; // rsm_reduce.comp per texel of a coarser level: four children of six images, six out
        cost.flops = 60;
        cost.fetches = 4 * 6;
        cost.bytesRead = 4 * (3 * 16 + 3 * 8);
        cost.bytesWritten = 3 * 16 + 3 * 8;
        auto t = timers.scope("rsm-mipmap", cost);
        for (int level = 0; level < settings_.levels; ++level) { // reduce()'s dispatches
            const int dst = settings_.size >> (level + 1);
            if (dst > 0) t.expectComputes(computeInvocations({dst, dst, viewCount()}, {8, 8, 1}));
        }
        reduce();
    }
}

void RsmPass::renderViews(Frame& frame)
{
    if (views_.empty()) return;
    program_.prepare(frame.gpuScene()); // the ALPHA_MASK variant for a scene with masks, once
    const int size = settings_.size;
    const bool pyramid = settings_.levels > 0;
    PassState state = PassState::fullscreen(fbo_, size, size);
    state.depthTest = true; // no culling: back faces occlude; the shader makes them reflect nothing
    state.apply();
    frame.bindSceneData();
    frame.gpuScene().baseColorTextures().bind(UNIT_BASE_COLOR);
    if (solidAngles_) solidAngles_.bind(UNIT_RSM_SOLID_ANGLES);
    program_.set("exactSolidAngle", settings_.exactSolidAngle ? 1 : 0);
    const float empty[4] = {0, 0, 0, 0}, noDepth[4] = {1e30f, 0, 0, 0}, nMin[4] = {2, 2, 2, 0},
                nMax[4] = {-2, -2, -2, 0};
    for (int i = 0; i < viewCount(); ++i) {
        const LightView& v = views_[i];
        fbo_.attachLayer(GL_COLOR_ATTACHMENT0, position_, i);
        fbo_.attachLayer(GL_COLOR_ATTACHMENT1, normal_, i);
        fbo_.attachLayer(GL_COLOR_ATTACHMENT2, flux_, i);
        if (pyramid) {
            fbo_.attachLayer(GL_COLOR_ATTACHMENT3, depthRange_, i);
            fbo_.attachLayer(GL_COLOR_ATTACHMENT4, normalMin_, i);
            fbo_.attachLayer(GL_COLOR_ATTACHMENT5, normalMax_, i);
        }
        fbo_.attach(GL_DEPTH_ATTACHMENT, depth_);
        if (i == 0) {
            if (pyramid)
                fbo_.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                     GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4, GL_COLOR_ATTACHMENT5});
            else
                fbo_.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2});
            fbo_.checkComplete();
        }
        for (int d = 0; d < 3; ++d) glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, d, empty);
        if (pyramid) {
            glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 3, noDepth);
            glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 4, nMin);
            glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 5, nMax);
        }
        const float one = 1.0f;
        glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &one);

        program_.set("viewProj", v.proj * v.view);
        program_.set("lightIndex", std::max(v.light, 0));
        program_.set("areaFirst", v.areaFirst);
        program_.set("areaCount", v.areaCount);
        program_.set("viewOrigin", v.origin);
        program_.set("viewDirection", v.direction);
        program_.set("orthographic", v.orthographic ? 1 : 0);
        program_.set("orthoTexelArea", orthoTexelArea(v));
        program_.set("equalSolidAngle", v.orthographic ? 0.0f : float(equalTexelSolidAngle(v.fovRad, size)));
        program_.set("viewLayer", i);
        program_.draw(frame.gpuScene());
    }
}

void RsmPass::reduce()
{
    position_.bindImage(0, GL_READ_WRITE, 0, GL_RGBA32F);
    normal_.bindImage(1, GL_READ_WRITE, 0, GL_RGBA32F);
    flux_.bindImage(2, GL_READ_WRITE, 0, GL_RGBA32F);
    depthRange_.bindImage(3, GL_READ_WRITE, 0, GL_RG32F);
    normalMin_.bindImage(4, GL_READ_WRITE, 0, GL_RGBA16F);
    normalMax_.bindImage(5, GL_READ_WRITE, 0, GL_RGBA16F);
    reduce_.set("size", settings_.size);
    reduce_.use();
    for (int level = 0; level < settings_.levels; ++level) {
        const int dst = settings_.size >> (level + 1);
        reduce_.set("level", level);
        // Level 0 was rendered, not stored through images: make those writes visible to image loads too.
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        glDispatchCompute(GLuint((dst + 7) / 8), GLuint((dst + 7) / 8), GLuint(viewCount()));
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void RsmPass::bind() const
{
    position_.bind(UNIT_RSM_FIRST + 0);
    normal_.bind(UNIT_RSM_FIRST + 1);
    flux_.bind(UNIT_RSM_FIRST + 2);
    if (settings_.levels > 0) {
        depthRange_.bind(UNIT_RSM_FIRST + 3);
        normalMin_.bind(UNIT_RSM_FIRST + 4);
        normalMax_.bind(UNIT_RSM_FIRST + 5);
    }
    if (viewsBuffer_) viewsBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_RSM_VIEWS);
}

} // namespace bounce::gl
