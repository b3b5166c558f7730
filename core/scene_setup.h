// Scene setups: a small JSON file that turns a downloaded glTF (most have no light and no camera, some are
// not in metres, some carry placeholder materials) into a scene that renders with light on the first try
// and can be compared with the path tracer. `--scene` accepts a setup wherever it accepts a glTF path.
//
//   {
//     "base": "cornell-area",                      optional: a built-in scene to start from
//     "gltf": "../../../shared/assets/x/x.gltf",   optional: relative to the setup file
//     "transform": {"scale": 0.01, "rotateYDeg": 90, "translate": [0, 0, 0]},   applied to the glTF
//     "materials": {"*": {...}, "gold": {...}},    overrides of the glTF's materials by name ("*": all):
//                  baseColor [r,g,b], metallic, roughness, specular, emission [r,g,b] W/(m^2 sr),
//                  baseColorTexture false, normalTexture false (drop the texture, or the normal map)
//     "floor": {"y": 0, "halfSize": 1, "albedo": [0.5, 0.5, 0.5]},   optional: a square floor, facing up
//     "camera": {"position": [x,y,z], "target": [x,y,z], "yfovDeg": 40},
//     "lights": [ ...lightFromJson... ]
//   }
//
// Unknown keys and wrong types are refused with SceneError naming the key; a missing glTF is refused
// naming the file. Units are the project's (DESIGN.md): metres, W/sr, W/m^2, radiance W/(m^2 sr).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/scene.h"

namespace bounce::core {

// Loads a setup file (SceneError on any problem).
Scene loadSetup(const std::string& path);

// Adds one light to the scene from its JSON description (`where` names it in error messages):
//   {"type": "point", "position": [x,y,z], "intensity": [r,g,b] | I}                 W/sr
//   {"type": "spot", "position": [..], "direction": [..] | "target": [..], "intensity": ..,
//    "outerDeg": 45, "innerDeg": 0}                                                   W/sr
//   {"type": "directional", "direction": [..], "irradiance": [r,g,b] | E}             W/m^2
//   {"type": "area", "corner": [..], "edge1": [..], "edge2": [..], "radiance": ..}    W/(m^2 sr), a
//    rectangle emitting on the side of edge1 x edge2 (added as an emissive mesh, like the Cornell light)
void addLightFromJson(Scene& scene, const nlohmann::json& light, const std::string& where);

// Sets the camera from {"position": [..], "target": [..] | "forward": [..], "up": [..], "yfovDeg": ..}.
void setCameraFromJson(Scene& scene, const nlohmann::json& camera, const std::string& where);

// The command-line forms (bounce render --camera/--light): "x,y,z:tx,ty,tz[:fovDeg]" and
// "TYPE:key=v[,v,v];key=v..." with the keys of addLightFromJson, e.g.
// "spot:position=0.278,0.54,0.279;direction=0,-1,0;intensity=10;outerDeg=30". Throw SceneError.
nlohmann::json cameraJsonFromArgument(const std::string& text);
nlohmann::json lightJsonFromArgument(const std::string& text);

} // namespace bounce::core
