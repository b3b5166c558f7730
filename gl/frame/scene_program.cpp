#include "gl/frame/scene_program.h"

#include <stdexcept>

namespace bounce::gl {

SceneProgram::SceneProgram(std::string label, std::string vertexPath, std::string fragmentPath,
                           std::vector<Define> defines)
    : label_(std::move(label)),
      vertexPath_(std::move(vertexPath)),
      fragmentPath_(std::move(fragmentPath)),
      defines_(std::move(defines)),
      plain_(Program::graphics(label_, vertexPath_, fragmentPath_, defines_))
{}

void SceneProgram::prepare(const GpuScene& scene)
{
    if (!scene.hasAlphaMask() || masked_) return;
    std::vector<Define> defines = defines_;
    for (const Define& d : scene.alphaMaskDefines()) defines.push_back(d);
    masked_ = Program::graphics(label_ + ".masked", vertexPath_, fragmentPath_, defines);
}

void SceneProgram::draw(const GpuScene& scene) const
{
    if (!scene.hasAlphaMask()) {
        plain_.use();
        scene.draw();
        return;
    }
    if (!masked_) throw std::logic_error(label_ + ": SceneProgram::prepare was not called for a masked scene");
    plain_.use();
    scene.draw(GpuScene::Meshes::Opaque);
    masked_.use();
    scene.draw(GpuScene::Meshes::Masked);
}

} // namespace bounce::gl
