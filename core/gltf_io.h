// glTF 2.0 in and out of core::Scene. Loading flattens the node hierarchy into world-space meshes,
// lights and one camera; writing produces a .gltf with a sibling .bin that loads back to the same
// Scene (same contentHash). Conventions as in DESIGN.md: light `intensity` is read as W/sr (W/m^2 for
// directional lights) and multiplies the light's colour; emission is emissiveFactor x
// KHR_materials_emissive_strength.
//
// What loading does with the parts of glTF the Scene has no room for:
// - only TRIANGLES primitives are read; other modes are skipped with a warning on stderr;
// - without NORMAL, flat normals are generated (each triangle gets its own three vertices);
// - without material, a primitive gets glTF's default material (white, metallic 1, roughness 1);
// - the baseColor texture is decoded (8-bit RGBA, sRGB as stored, alpha kept for MASK materials), and
//   only TEXCOORD_0 is read; a metallicRoughness texture's mean (blue: metallic, green: roughness)
//   multiplies metallicFactor and roughnessFactor (Bounce has no per-texel metallic or roughness);
//   samplers, occlusion/emissive textures are ignored; alphaMode MASK is kept with its alphaCutoff and
//   baseColorFactor's alpha, BLEND is drawn OPAQUE with a warning;
// - the normalTexture is decoded as it is stored (linear) with its scale, and a normal-mapped primitive's
//   TANGENT is read (made unit, the handedness +-1, flipped with a mirroring node). Where the file has no
//   usable tangents they are computed from TEXCOORD_0 (core::tangentsFromUvs: per-vertex sums, not
//   MikkTSpace, so across uv seams they may differ from the authoring tool's), with a warning; without
//   TEXCOORD_0 the map is ignored for that primitive, with a warning. A normal texture read through
//   another TEXCOORD is ignored with a warning;
// - the first perspective camera met in a depth-first walk of the scene is used. Without zfar (an
//   infinite projection) zfar becomes twice the distance from the camera to the farthest corner of the
//   scene's bounds, which keeps every surface inside the frustum with usable depth precision.
//   Without any camera, a default one looks along +z at the bounds, far enough back that their front
//   face fills the canonical field of view;
// - light `range` is ignored (lights follow the inverse square law everywhere); a point light keeps the
//   default Light::direction, since it has none;
// - a node hierarchy that is not a tree (without a scene too), indices or offsets outside their buffers,
//   counts over 2^28, index accessors that are not unsigned integers, URIs that leave the file's folder
//   (absolute, '..', or through a symbolic link) or name no file ("", ".", a folder), missing buffers or
//   images, images whose header claims more than 2^26 pixels or none, and non-finite positions are
//   errors (SceneError); ranges are checked before data is read;
// - values glTF forbids are refused (SceneError), never clamped, so that the rasteriser and the path
//   tracer cannot disagree about them: a negative light intensity or colour, a spot cone outside
//   0 <= inner < outer <= pi/2, a camera yfov outside (0, pi), znear <= 0 or zfar <= znear, a fractional
//   light index.
//
// What writing keeps: everything contentHash covers, bit for bit (numbers are written as the shortest
// decimal that reads back as the same float), plus names and the camera. Not kept: meshes without
// triangles (glTF has no empty accessors), textures no material uses (loading only decodes base
// colour textures), a point light's direction, and the sign of zero components of light and camera
// directions (read back as +0). A hard spot cone (inner == outer) is written with innerConeAngle one double below
// outerConeAngle, as glTF requires inner < outer; it reads back as inner == outer.
//
// Where it lives: core/gltf_read.cpp (loading), core/gltf_write.cpp (writing), core/gltf_files.* (the
// folder jail and tinygltf's file callbacks, which decide what a scene may read).
#pragma once

#include <stdexcept>
#include <string>

#include "core/scene.h"

namespace bounce::core {

// Thrown for a scene that cannot be read or written; the message names the file and the problem.
struct SceneError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Loads a .gltf (with its external buffers and images, which must lie in the file's folder or below)
// or a .glb. Throws SceneError for malformed, truncated or unsafe input and for non-finite data.
Scene loadGltf(const std::string& path);

// Writes path (.gltf) and a sibling .bin with the same stem, each atomically. Uses
// KHR_lights_punctual, KHR_materials_specular and KHR_materials_emissive_strength where the scene
// needs them. Meshes without triangles are not written.
void writeGltf(const Scene& scene, const std::string& path);

} // namespace bounce::core
