// cornell-spot with its spot replaced by a directional light shining through the open front of the box
// (down and in, so that the floor, the back wall and the blocks' shadows are lit): the one light kind
// no Cornell variant has. Shared by the tests of direct light and of shadow filtering.
#pragma once

#include <glm/glm.hpp>

#include "core/cornell.h"

namespace bounce::test {

inline core::Scene cornellDirectional()
{
    core::Scene s = core::makeCornell("cornell-spot");
    core::Light sun;
    sun.name = "sun";
    sun.type = core::LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.25f, -0.6f, 1.0f));
    sun.intensity = glm::vec3(3.0f, 2.8f, 2.5f); // W/m^2
    s.lights = {sun};
    return s;
}

} // namespace bounce::test
