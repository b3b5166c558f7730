// The probe field of `ddgi` (Majercik et al. 2019; relocation and classification: Majercik et al. 2021): a
// grid of probes over the scene's bounds, each with an octahedral irradiance map and a map of the
// moments of the distance to what its rays hit, in two atlases (glsl/technique/ddgi/probes.glsl says how
// they are laid out). It lives in world space: the camera never touches it, and a change of the scene's
// lights or geometry is absorbed by the hysteresis of its updates, not by a restart.
//
//   ProbeField field(frame, settings);
//   field.update(frame, timers);  // cast the rays, relocate and classify, blend them into the atlases
//   field.shade(frame, timers);   // every pixel's indirect light from the probes into frame.indirect()
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/frame/direct_lit_program.h"
#include "gl/frame/frame.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

// Probe (x, y, z) sits at origin + (x, y, z) spacing (plus its relocation offset).
struct ProbeGrid {
    glm::vec3 origin{0.0f};
    glm::vec3 spacing{1.0f};
    glm::ivec3 counts{2};
    int probes() const { return counts.x * counts.y * counts.z; }
};

// At most `budget` probes (at least 8) over the bounds, in cells as near to cubes as whole counts allow
// (the paper's uniform spacing): each side divided into its length over the cell size, rounded, at least 2,
// with the smallest cell size whose grid fits the budget. Every probe sits at the centre of its cell, so
// that none lies on the bounds' faces (a closed room's walls). A flat or empty extent takes a thousandth
// of the longest side (or 1 m) so that no spacing is zero.
ProbeGrid probeGridFor(const core::Bounds& bounds, int budget);

struct ProbeFieldSettings {
    int probes = 256;       // the grid's budget (probeGridFor)
    int raysPerProbe = 256; // rotated rays, blended into the atlases
    int fixedRays = 32;     // fixed rays for relocation and classification (0 without both)
    float hysteresis = 0.97f;
    bool fastTransitions = true; // less hysteresis where the estimate changed much (2021)
    bool bounces = true;         // hits reflect the probes' last irradiance (the paper's infinite bounces)
    bool relocation = true;
    bool classification = true;
    float selfShadowBias = 0.3f;
};

class ProbeField {
public:
    ProbeField(const Frame& frame, const ProbeFieldSettings& settings);

    void update(Frame& frame, PassTimers& timers);
    void shade(Frame& frame, PassTimers& timers);

    const ProbeGrid& grid() const { return grid_; }
    int atlasColumns() const { return columns_; }
    const Texture& irradiance() const { return irradiance_; }
    const Texture& depth() const { return depth_; }
    // Per probe: xyz its relocation offset, w 1 active, 0 inactive (read back).
    std::vector<glm::vec4> probeStates() const;
    int updates() const { return updates_; }
    const Buffer& rays() const { return rays_; }
    double raysPerFrame() const;

    static constexpr int kIrradianceTile = 8; // texels per side, border included (probes.glsl)
    static constexpr int kDepthTile = 16;

private:
    void setGrid(Program& program) const;
    glm::mat3 rotation() const; // this update's random rotation of the rotated rays

    ProbeFieldSettings settings_;
    ProbeGrid grid_;
    int columns_ = 1, rows_ = 1;
    float maxDistance_ = 1.0f;
    Texture irradiance_, depth_;
    Buffer states_, rays_;
    DirectLitProgram trace_;
    Program state_, updateIrradiance_, updateDepth_, shade_;
    int updates_ = 0;
};

} // namespace bounce::gl
