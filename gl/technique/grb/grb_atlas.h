// The texture atlas on the GPU (Hermes et al. 2010, Sec. 4.1): the parameterisation of core/atlas.h, the
// atlas corners of every triangle (SSBO), and the static atlases rendered once per scene: position and
// material, shading and face normal, base colour (glsl/technique/grb/atlas.glsl).
#pragma once

#include "core/atlas.h"
#include "gl/frame/frame.h"
#include "gl/resource/buffer.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class GrbAtlas {
public:
    GrbAtlas(const core::Scene& scene, const core::AtlasSettings& settings);

    // Renders the static atlases (pass "atlas") and counts the filled texels.
    void fill(const Frame& frame, PassTimers& timers);
    // The corners SSBO at SSBO_GRB_ATLAS_CORNERS, the static atlases at UNIT_GRB_POSITION..BASE_COLOR.
    void bind() const;

    const core::Atlas& layout() const { return atlas_; }
    int width() const { return atlas_.width; }
    int height() const { return atlas_.height; }
    std::size_t filledTexels() const { return filled_; }
    const Texture& position() const { return position_; }
    const Texture& normal() const { return normal_; }
    const Texture& baseColor() const { return baseColor_; }

private:
    core::Atlas atlas_;
    Buffer corners_, charts_;
    Texture position_, normal_, baseColor_, depth_;
    Framebuffer fbo_;
    VertexArray vao_;
    Program program_;
    std::size_t filled_ = 0;
};

} // namespace bounce::gl
