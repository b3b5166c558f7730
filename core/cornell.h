// The canonical Cornell box (shared/scenes/cornell-box.md) built from its published numbers, and the
// one entry point that turns a scene argument (a built-in name or a glTF path) into a Scene.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/scene.h"

namespace bounce::core {

// "cornell-area", "cornell-spot", "cornell-point", the hard variant "cornell-point-ceiling" (the point
// light 1 mm under the ceiling) and "cornell-slats" (cornell-spot with a row of slats and a shelf: more
// depth complexity; the project's own, not cornell-box.md's) and "cornell-glossy" (cornell-area with the
// tall block a rough white metal: glossy transfer and glossy final gathering). Throws SceneError
// (gltf_io.h) for any other name.
Scene makeCornell(std::string_view variant);

// The names makeCornell accepts, canonical variants first.
std::vector<std::string> builtinSceneNames();

// A built-in name gives the generated scene; a .gltf/.glb path is read by loadGltf, a .json path is a
// scene setup (core/scene_setup.h).
Scene loadScene(const std::string& nameOrPath);

} // namespace bounce::core
