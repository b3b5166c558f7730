// The reflective shadow map (RSM) of every light of the frame (Dachsbacher & Stamminger 2005; Nichols,
// Shopf & Wyman 2009 §3.2.2-3.4), and its light-space min-max pyramid (§3.4): a frame service for every
// technique that starts from the light's first bounce (VPLs, photon emission, point lighting). Layout and
// the meaning of every channel: glsl/common/rsm.glsl; shaders glsl/frame/rsm.{vert,frag}, rsm_reduce.comp.
// Views (gl/frame/light_views.h, the same builder as the shadow maps):
//   spot (outer cone <= 60 deg)   one perspective view, field of view 2 x the outer cone
//   point, wider spot             six cube faces (90 deg each)
//   area (an emitting mesh)       six cube faces around its centroid; a cosine-lobe point emitter
//   directional                   one orthographic view fitted to the scene's bounds
// Texel solid angle: Eq. 4 (omega_frustum / size^2 for every texel) by default, or the exact solid angle
// of each perspective texel (exactSolidAngle). Passes timed: "rsm", and "rsm-mipmap" when levels > 0.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/frame/frame.h"
#include "gl/frame/light_views.h"
#include "gl/frame/params.h"
#include "gl/frame/scene_program.h"
#include "gl/resource/buffer.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

struct RsmSettings {
    int size = 256;               // texels per side of each view
    bool exactSolidAngle = false; // exact per-texel solid angle instead of Eq. 4
    int levels = 0;               // pyramid levels above the RSM (0: the RSM only); needs a power-of-two size
};

// The parameters every technique that renders an RSM declares, once: "rsmSize" (4..2048; a technique
// that needs a power of two or a smaller map checks it when created, see requireRsmSize) and
// "exactSolidAngle". Aggregate rows in ParamDecl's field order.
std::vector<ParamDecl> rsmParams();
// RsmSettings from those parameters (levels 0: the technique sets the pyramid it needs).
RsmSettings rsmSettingsFrom(const ParamValues& values);
// Throws std::invalid_argument naming `technique` when `size` is not a power of two (powerOfTwo) or
// exceeds maxSize.
void requireRsmSize(const std::string& technique, int size, bool powerOfTwo, int maxSize = 2048);

class RsmPass {
public:
    explicit RsmPass(const RsmSettings& settings);

    // Renders the RSM of every light of the frame (rebuilding the views, which follow moving lights),
    // then the pyramid levels.
    void render(Frame& frame, PassTimers& timers);
    // Binds the RSM textures and the views SSBO for the passes that read them.
    void bind() const;

    const RsmSettings& settings() const { return settings_; }
    int size() const { return settings_.size; }
    int levels() const { return settings_.levels; }
    int viewCount() const { return int(views_.size()); }
    const std::vector<LightView>& views() const { return views_; }
    // Atlas layers (width size * 3/2 when levels > 0, else size; height size; one layer per view).
    const Texture& position() const { return position_; }
    const Texture& normal() const { return normal_; }
    const Texture& flux() const { return flux_; }
    const Texture& depthRange() const { return depthRange_; } // allocated only when levels > 0
    const Texture& normalMin() const { return normalMin_; }   // allocated only when levels > 0
    const Texture& normalMax() const { return normalMax_; }   // allocated only when levels > 0

    // The side of a texel at the view's centre: at distance 1 (perspective) or in metres (orthographic).
    float texelSide(const LightView& v) const { return v.texelSide(settings_.size); }
    // An orthographic view's texel area perpendicular to the light (m^2).
    float orthoTexelArea(const LightView& v) const { return v.orthographic ? texelSide(v) * texelSide(v) : 0.0f; }
    // Eq. 4's solid angle of one texel of a square perspective view of field of view fov: the frustum's
    // solid angle 4 asin(sin^2(fov/2)) over size^2 texels (steradians).
    static double equalTexelSolidAngle(double fovRad, int size);
    // The exact solid angle of texel (x, y) of that view (steradians), row 0 at the bottom.
    static double exactTexelSolidAngle(double fovRad, int size, int x, int y);

private:
    RsmSettings settings_;
    std::vector<LightView> views_;
    Texture position_, normal_, flux_, depthRange_, normalMin_, normalMax_, depth_, solidAngles_;
    std::vector<float> solidAngleFovs_; // the field of view each layer of solidAngles_ was computed for
    Framebuffer fbo_;
    SceneProgram program_;
    Program reduce_;
    Buffer viewsBuffer_;

    void buildViews(const Frame& frame);
    void allocate(int layers);
    void updateSolidAngles();
    void renderViews(Frame& frame);
    void reduce();
};

} // namespace bounce::gl
