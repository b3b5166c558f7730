#include "core/scene_setup.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/cornell.h"
#include "core/gltf_io.h"

namespace bounce::core {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& where, const std::string& problem)
{
    throw SceneError(where + ": " + problem);
}

void allowOnly(const json& j, const std::string& where, std::initializer_list<const char*> keys)
{
    if (!j.is_object()) fail(where, "needs a JSON object");
    for (const auto& item : j.items()) {
        // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
        const std::string& key = item.key();
        if (std::find_if(keys.begin(), keys.end(), [&](const char* k) { return key == k; }) != keys.end()) continue;
        std::string allowed;
        for (const char* k : keys) allowed += std::string(allowed.empty() ? "" : ", ") + k;
        fail(where, "unknown key '" + key + "' (allowed: " + allowed + ")");
    }
}

float number(const json& j, const std::string& where, const std::string& key)
{
    if (!j.is_number()) fail(where, "'" + key + "' needs a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(where, "'" + key + "' is not finite");
    return float(v);
}

float number(const json& obj, const std::string& where, const std::string& key, float fallback)
{
    return obj.contains(key) ? number(obj[key], where, key) : fallback;
}

glm::vec3 vec3(const json& j, const std::string& where, const std::string& key)
{
    if (!j.is_array() || j.size() != 3) fail(where, "'" + key + "' needs [x, y, z]");
    return {number(j[0], where, key), number(j[1], where, key), number(j[2], where, key)};
}

glm::vec3 required3(const json& obj, const std::string& where, const std::string& key)
{
    if (!obj.contains(key)) fail(where, "needs '" + key + "'");
    return vec3(obj[key], where, key);
}

// A colour: [r, g, b] or one number for grey, non-negative.
glm::vec3 colour(const json& obj, const std::string& where, const std::string& key)
{
    if (!obj.contains(key)) fail(where, "needs '" + key + "'");
    const json& j = obj[key];
    const glm::vec3 c = j.is_number() ? glm::vec3(number(j, where, key)) : vec3(j, where, key);
    if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) fail(where, "'" + key + "' must not be negative");
    return c;
}

glm::vec3 unit(const glm::vec3& v, const std::string& where, const std::string& key)
{
    const float len = glm::length(v);
    if (!(len > 0.0f)) fail(where, "'" + key + "' has no direction (zero length)");
    return v / len;
}

void addMesh(Scene& scene, std::vector<glm::vec3> positions, std::vector<std::uint32_t> indices, const Material& m,
             const std::string& name)
{
    scene.materials.push_back(m);
    Mesh mesh;
    mesh.name = name;
    const glm::vec3 n = glm::normalize(glm::cross(positions[1] - positions[0], positions[2] - positions[0]));
    mesh.normals.assign(positions.size(), n);
    mesh.positions = std::move(positions);
    mesh.indices = std::move(indices);
    mesh.material = std::uint32_t(scene.materials.size() - 1);
    scene.meshes.push_back(std::move(mesh));
}

void applyTransform(Scene& scene, std::size_t firstMesh, const json& t, const std::string& where)
{
    allowOnly(t, where, {"scale", "rotateYDeg", "translate"});
    const float scale = number(t, where, "scale", 1.0f);
    if (!(scale > 0.0f)) fail(where, "'scale' must be > 0");
    const float angle = glm::radians(number(t, where, "rotateYDeg", 0.0f));
    const glm::vec3 translate = t.contains("translate") ? vec3(t["translate"], where, "translate") : glm::vec3(0.0f);
    const glm::mat3 rotate = glm::mat3(glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0)));
    for (std::size_t i = firstMesh; i < scene.meshes.size(); ++i) {
        for (glm::vec3& p : scene.meshes[i].positions) p = rotate * (scale * p) + translate;
        for (glm::vec3& n : scene.meshes[i].normals) n = rotate * n; // uniform scale keeps normals
        for (glm::vec4& t : scene.meshes[i].tangents) t = glm::vec4(rotate * glm::vec3(t), t.w);
    }
    for (Light& l : scene.lights) {
        l.position = rotate * (scale * l.position) + translate;
        l.direction = rotate * l.direction;
    }
    Camera& c = scene.camera;
    c.position = rotate * (scale * c.position) + translate;
    c.forward = rotate * c.forward;
    c.up = rotate * c.up;
}

void overrideMaterial(Material& m, const json& o, const std::string& where)
{
    allowOnly(o, where,
              {"baseColor", "metallic", "roughness", "specular", "emission", "baseColorTexture", "normalTexture"});
    if (o.contains("baseColor")) m.baseColor = colour(o, where, "baseColor");
    if (o.contains("metallic")) m.metallic = std::clamp(number(o["metallic"], where, "metallic"), 0.0f, 1.0f);
    if (o.contains("roughness")) m.roughness = std::clamp(number(o["roughness"], where, "roughness"), 0.0f, 1.0f);
    if (o.contains("specular")) m.specular = std::clamp(number(o["specular"], where, "specular"), 0.0f, 1.0f);
    if (o.contains("emission")) m.emission = colour(o, where, "emission");
    if (o.contains("baseColorTexture")) {
        if (!o["baseColorTexture"].is_boolean() || o["baseColorTexture"].get<bool>())
            fail(where, "'baseColorTexture' can only be false (drop the texture)");
        m.baseColorTexture = -1;
    }
    if (o.contains("normalTexture")) {
        if (!o["normalTexture"].is_boolean() || o["normalTexture"].get<bool>())
            fail(where, "'normalTexture' can only be false (drop the normal map)");
        m.normalTexture = -1;
    }
}

// Appends `add` to `scene`: meshes, materials and textures re-indexed, lights appended.
void merge(Scene& scene, Scene add)
{
    const auto materialBase = std::uint32_t(scene.materials.size());
    const int textureBase = int(scene.textures.size());
    for (Material& m : add.materials) {
        if (m.baseColorTexture >= 0) m.baseColorTexture += textureBase;
        if (m.normalTexture >= 0) m.normalTexture += textureBase;
        scene.materials.push_back(std::move(m));
    }
    for (Texture& t : add.textures) scene.textures.push_back(std::move(t));
    for (Mesh& m : add.meshes) {
        m.material += materialBase;
        scene.meshes.push_back(std::move(m));
    }
    for (Light& l : add.lights) scene.lights.push_back(std::move(l));
}

} // namespace

void addLightFromJson(Scene& scene, const json& l, const std::string& where)
{
    if (!l.is_object() || !l.contains("type") || !l["type"].is_string())
        fail(where, "a light needs \"type\": point, spot, directional or area");
    const std::string type = l["type"].get<std::string>();
    Light light;
    light.name = where;
    if (type == "point") {
        allowOnly(l, where, {"type", "position", "intensity"});
        light.type = LightType::Point;
        light.position = required3(l, where, "position");
        light.intensity = colour(l, where, "intensity");
    } else if (type == "spot") {
        allowOnly(l, where, {"type", "position", "direction", "target", "intensity", "outerDeg", "innerDeg"});
        light.type = LightType::Spot;
        light.position = required3(l, where, "position");
        if (l.contains("direction") == l.contains("target")) fail(where, "a spot needs 'direction' or 'target' (one)");
        light.direction = unit(l.contains("direction") ? vec3(l["direction"], where, "direction")
                                                       : vec3(l["target"], where, "target") - light.position,
                               where, l.contains("direction") ? "direction" : "target");
        light.intensity = colour(l, where, "intensity");
        const float outer = number(l, where, "outerDeg", 45.0f), inner = number(l, where, "innerDeg", 0.0f);
        if (!(outer > 0.0f && outer <= 90.0f)) fail(where, "'outerDeg' must be in (0, 90] (glTF's cone)");
        if (!(inner >= 0.0f && inner <= outer)) fail(where, "'innerDeg' must be in [0, outerDeg]");
        light.outerConeRad = glm::radians(outer);
        light.innerConeRad = glm::radians(inner);
    } else if (type == "directional") {
        allowOnly(l, where, {"type", "direction", "irradiance"});
        light.type = LightType::Directional;
        light.direction = unit(required3(l, where, "direction"), where, "direction");
        light.intensity = colour(l, where, "irradiance");
    } else if (type == "area") {
        allowOnly(l, where, {"type", "corner", "edge1", "edge2", "radiance"});
        const glm::vec3 c = required3(l, where, "corner"), e1 = required3(l, where, "edge1"),
                        e2 = required3(l, where, "edge2");
        if (!(glm::length(glm::cross(e1, e2)) > 0.0f)) fail(where, "'edge1' and 'edge2' span no area");
        Material m;
        m.name = where;
        m.baseColor = glm::vec3(0.0f);
        m.specular = 0.0f;
        m.emission = colour(l, where, "radiance");
        addMesh(scene, {c, c + e1, c + e1 + e2, c + e2}, {0, 1, 2, 0, 2, 3}, m, where);
        return;
    } else {
        fail(where, "unknown light type '" + type + "' (point, spot, directional, area)");
    }
    scene.lights.push_back(light);
}

void setCameraFromJson(Scene& scene, const json& c, const std::string& where)
{
    allowOnly(c, where, {"position", "target", "forward", "up", "yfovDeg"});
    Camera cam = scene.camera;
    cam.position = required3(c, where, "position");
    if (c.contains("target") == c.contains("forward")) fail(where, "needs 'target' or 'forward' (one)");
    cam.forward = unit(c.contains("forward") ? vec3(c["forward"], where, "forward")
                                             : vec3(c["target"], where, "target") - cam.position,
                       where, "target");
    const glm::vec3 up = c.contains("up") ? vec3(c["up"], where, "up") : glm::vec3(0, 1, 0);
    const glm::vec3 right = glm::cross(cam.forward, up);
    if (!(glm::length(right) > 1e-6f)) fail(where, "'up' is parallel to the view direction");
    cam.up = glm::normalize(glm::cross(glm::normalize(right), cam.forward));
    const float fov = number(c, where, "yfovDeg", glm::degrees(cam.yfovRad));
    if (!(fov > 0.0f && fov < 180.0f)) fail(where, "'yfovDeg' must be in (0, 180)");
    cam.yfovRad = glm::radians(fov);
    scene.camera = cam;
}

Scene loadSetup(const std::string& path)
{
    std::ifstream in(path);
    if (!in) fail(path, "cannot open the scene setup");
    json setup;
    try {
        setup = json::parse(in);
    } catch (const json::exception& e) {
        fail(path, std::string("malformed JSON: ") + e.what());
    }
    allowOnly(setup, path, {"base", "gltf", "transform", "materials", "floor", "camera", "lights", "comment"});
    Scene scene;
    if (setup.contains("base")) {
        if (!setup["base"].is_string()) fail(path, "'base' needs a built-in scene name");
        scene = makeCornell(setup["base"].get<std::string>());
    }
    if (setup.contains("gltf")) {
        if (!setup["gltf"].is_string()) fail(path, "'gltf' needs a path");
        const fs::path gltf = fs::path(path).parent_path() / setup["gltf"].get<std::string>();
        if (!fs::exists(gltf))
            fail(path, "its glTF " + gltf.lexically_normal().string() +
                           " is not there (the benchmark assets live in ../shared/assets beside the project)");
        Scene loaded = loadGltf(gltf.string());
        const std::size_t firstMesh = 0;
        if (setup.contains("transform")) applyTransform(loaded, firstMesh, setup["transform"], path + ": transform");
        if (setup.contains("materials")) {
            const json& overrides = setup["materials"];
            if (!overrides.is_object()) fail(path, "'materials' needs an object of name: overrides");
            for (const auto& [name, o] : overrides.items()) {
                bool found = name == "*";
                for (Material& m : loaded.materials)
                    if (name == "*" || m.name == name)
                        overrideMaterial(m, o, path + ": material '" + name + "'"), found = true;
                if (!found) fail(path, "no material named '" + name + "' in the glTF");
            }
        }
        const bool hadScene = !scene.meshes.empty();
        if (!hadScene) {
            const std::string source = loaded.cameraSource;
            scene.camera = loaded.camera;
            scene.cameraSource = source;
        }
        merge(scene, std::move(loaded));
    }
    if (setup.contains("floor")) {
        const json& f = setup["floor"];
        const std::string where = path + ": floor";
        allowOnly(f, where, {"y", "halfSize", "albedo", "centre"});
        const float y = number(f, where, "y", 0.0f), h = number(f, where, "halfSize", 1.0f);
        if (!(h > 0.0f)) fail(where, "'halfSize' must be > 0");
        const glm::vec3 c = f.contains("centre") ? vec3(f["centre"], where, "centre") : glm::vec3(0.0f);
        Material m;
        m.name = "floor";
        m.baseColor = f.contains("albedo") ? colour(f, where, "albedo") : glm::vec3(0.5f);
        m.specular = 0.0f;
        addMesh(scene, {{c.x - h, y, c.z - h}, {c.x - h, y, c.z + h}, {c.x + h, y, c.z + h}, {c.x + h, y, c.z - h}},
                {0, 1, 2, 0, 2, 3}, m, "floor");
    }
    if (setup.contains("lights")) {
        if (!setup["lights"].is_array()) fail(path, "'lights' needs an array");
        int i = 0;
        for (const json& l : setup["lights"]) addLightFromJson(scene, l, path + ": light " + std::to_string(i++));
    }
    if (setup.contains("camera")) {
        setCameraFromJson(scene, setup["camera"], path + ": camera");
        scene.cameraSource = "setup";
    }
    if (scene.meshes.empty()) fail(path, "the setup has no geometry (give 'base' or 'gltf')");
    scene.name = fs::path(path).stem().string();
    // A setup's own geometry may reach beyond the glTF's: keep the far plane beyond the whole scene.
    const Bounds b = scene.bounds();
    const float diagonal = glm::length(b.extent());
    scene.camera.zfar = std::max(scene.camera.zfar, glm::length(scene.camera.position - b.centre()) + diagonal);
    if (const std::string err = scene.validate(); !err.empty()) fail(path, "invalid scene: " + err);
    return scene;
}

namespace {

std::vector<std::string> split(const std::string& text, char sep)
{
    std::vector<std::string> parts;
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, sep)) parts.push_back(part);
    return parts;
}

// "1,2,3" -> [1,2,3]; "4" -> 4.
json numbersJson(const std::string& text, const std::string& where)
{
    json values = json::array();
    for (const std::string& v : split(text, ',')) {
        std::size_t used = 0;
        double d = 0.0;
        try {
            d = std::stod(v, &used);
        } catch (...) {
            used = 0;
        }
        if (used == 0 || used != v.size()) fail(where, "'" + v + "' is not a number");
        values.push_back(d);
    }
    if (values.size() == 1) return values[0];
    if (values.size() != 3) fail(where, "'" + text + "' needs one number or three");
    return values;
}

} // namespace

json cameraJsonFromArgument(const std::string& text)
{
    const std::string where = "--camera '" + text + "'";
    const std::vector<std::string> parts = split(text, ':');
    if (parts.size() < 2 || parts.size() > 3) fail(where, "needs POSITION:TARGET[:FOV_DEGREES], e.g. 0,1,3:0,1,0:40");
    json c = {{"position", numbersJson(parts[0], where)}, {"target", numbersJson(parts[1], where)}};
    if (parts.size() == 3) c["yfovDeg"] = numbersJson(parts[2], where);
    return c;
}

json lightJsonFromArgument(const std::string& text)
{
    const std::string where = "--light '" + text + "'";
    const auto colon = text.find(':');
    if (colon == std::string::npos)
        fail(where, "needs TYPE:key=value;key=value, e.g. point:position=0,1,0;intensity=5");
    json l = {{"type", text.substr(0, colon)}};
    for (const std::string& kv : split(text.substr(colon + 1), ';')) {
        if (kv.empty()) continue;
        const auto eq = kv.find('=');
        if (eq == std::string::npos || eq == 0) fail(where, "'" + kv + "' needs key=value");
        l[kv.substr(0, eq)] = numbersJson(kv.substr(eq + 1), where);
    }
    return l;
}

} // namespace bounce::core
