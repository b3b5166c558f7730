#include "core/camera_path.h"

#include <algorithm>
#include <fstream>

#include "core/gltf_io.h"
#include "core/scene_setup.h"

namespace bounce::core {

namespace {

using nlohmann::json;

constexpr int kMaxFrames = 100000; // render --frames' limit

[[noreturn]] void fail(const std::string& where, const std::string& problem)
{
    throw CameraPathError(where + ": " + problem);
}

void allowOnly(const json& j, const std::string& where, const std::vector<std::string>& keys,
               const std::vector<std::string>& required)
{
    if (!j.is_object()) fail(where, "needs a JSON object");
    std::string allowed;
    for (const std::string& k : keys) allowed += (allowed.empty() ? "" : ", ") + k;
    for (const auto& item : j.items())
        if (std::find(keys.begin(), keys.end(), item.key()) == keys.end())
            fail(where, "unknown key '" + item.key() + "' (allowed: " + allowed + ")");
    for (const std::string& k : required)
        if (!j.contains(k)) fail(where, "'" + k + "' is missing");
}

int integer(const json& j, const std::string& where, const std::string& key, int lo, int hi)
{
    if (!j.is_number_integer()) fail(where, "'" + key + "' needs an integer");
    const long long v = j.get<long long>();
    if (v < lo || v > hi)
        fail(where,
             "'" + key + "' is " + std::to_string(v) + ", outside " + std::to_string(lo) + ".." + std::to_string(hi));
    return int(v);
}

glm::vec3 vec3Of(const json& j)
{
    return {j[0].get<float>(), j[1].get<float>(), j[2].get<float>()};
}

// The camera of a key or of a frame between keys through the command line's own check (setCameraFromJson:
// finite values, a field of view in (0, 180), a view not along the up axis), after our own for a
// zero-length view, which it would call a target without direction.
Camera checkedCamera(const CameraKey& k, const Camera& base, const std::string& where)
{
    if (!(glm::length(k.target - k.position) > 0.0f))
        fail(where, "the position equals the target: a zero-length view has no direction");
    Scene scratch;
    scratch.camera = base;
    const json c = {{"position", {k.position.x, k.position.y, k.position.z}},
                    {"target", {k.target.x, k.target.y, k.target.z}},
                    {"yfovDeg", k.yfovDeg}};
    try {
        setCameraFromJson(scratch, c, where);
    } catch (const SceneError& e) {
        throw CameraPathError(e.what());
    }
    return scratch.camera;
}

CameraKey parseKey(const json& j, int frames, const std::string& where)
{
    allowOnly(j, where, {"frame", "camera"}, {"frame", "camera"});
    CameraKey k;
    k.frame = integer(j["frame"], where, "frame", 0, frames - 1);
    if (!j["camera"].is_string()) fail(where, "'camera' needs a string POSITION:TARGET:FOV_DEGREES");
    const std::string text = j["camera"].get<std::string>();
    json c;
    try {
        c = cameraJsonFromArgument(text);
        // Said plainly here, before the command line's check calls it a target without direction.
        if (c["position"] == c["target"])
            fail(where, "camera '" + text + "': the position equals the target: a zero-length view has no direction");
        // The command line's checks (NaN, Inf, three numbers each, the field of view's range) on a scratch scene.
        Scene scratch;
        setCameraFromJson(scratch, c, "camera '" + text + "'");
    } catch (const SceneError& e) {
        fail(where, e.what());
    }
    if (!c.contains("yfovDeg"))
        fail(where, "camera '" + text + "' needs its field of view: POSITION:TARGET:FOV_DEGREES");
    k.position = vec3Of(c["position"]);
    k.target = vec3Of(c["target"]);
    k.yfovDeg = c["yfovDeg"].get<float>();
    return k;
}

LightKey parseLights(const json& j, int frames, const std::string& where)
{
    allowOnly(j, where, {"frame", "light"}, {"frame", "light"});
    LightKey k;
    k.frame = integer(j["frame"], where, "frame", 0, frames - 1);
    if (!j["light"].is_array())
        fail(where, "'light' needs an array of --light specs, e.g. [\"point:position=0,1,0;intensity=5\"]");
    Scene scratch;
    for (const json& spec : j["light"]) {
        if (!spec.is_string()) fail(where, "each light needs a string TYPE:key=value;...");
        const std::string text = spec.get<std::string>();
        try {
            const json l = lightJsonFromArgument(text);
            if (l["type"] == "area")
                fail(where, "light '" + text +
                                "': an area light is geometry, which a path does not change "
                                "(point, spot and directional lights only)");
            addLightFromJson(scratch, l, "light '" + text + "'");
        } catch (const SceneError& e) {
            fail(where, e.what());
        }
    }
    k.lights = std::move(scratch.lights);
    return k;
}

template <typename Key>
void checkIncreasing(const std::vector<Key>& keys, const std::string& where, const std::string& list)
{
    for (std::size_t i = 1; i < keys.size(); ++i)
        if (keys[i].frame <= keys[i - 1].frame)
            fail(where, "'" + list + "' frames must strictly increase, but entry " + std::to_string(i) + " (frame " +
                            std::to_string(keys[i].frame) + ") follows frame " + std::to_string(keys[i - 1].frame));
}

} // namespace

CameraKey CameraPath::at(int frame) const
{
    if (frame <= keys.front().frame) return {frame, keys.front().position, keys.front().target, keys.front().yfovDeg};
    if (frame >= keys.back().frame) return {frame, keys.back().position, keys.back().target, keys.back().yfovDeg};
    // The last key at or before the frame, and the next.
    const auto next =
        std::upper_bound(keys.begin(), keys.end(), frame, [](int f, const CameraKey& k) { return f < k.frame; });
    const CameraKey& a = *(next - 1);
    const CameraKey& b = *next;
    const float t = float(frame - a.frame) / float(b.frame - a.frame);
    return {frame, glm::mix(a.position, b.position, t), glm::mix(a.target, b.target, t),
            a.yfovDeg + (b.yfovDeg - a.yfovDeg) * t};
}

Camera CameraPath::camera(int frame, const Camera& base) const
{
    return checkedCamera(at(frame), base, "frame " + std::to_string(frame));
}

const std::vector<Light>* CameraPath::lightsAt(int frame) const
{
    const std::vector<Light>* lights = nullptr;
    for (const LightKey& k : lightKeys)
        if (k.frame <= frame) lights = &k.lights;
    return lights;
}

bool CameraPath::lightsChangeAt(int frame) const
{
    return std::any_of(lightKeys.begin(), lightKeys.end(), [&](const LightKey& k) { return k.frame == frame; });
}

CameraPath parseCameraPath(const json& j, const std::string& where)
{
    allowOnly(j, where, {"frames", "keys", "lights", "comment"}, {"frames", "keys"});
    CameraPath path;
    path.frames = integer(j["frames"], where, "frames", 1, kMaxFrames);
    if (!j["keys"].is_array() || j["keys"].empty())
        fail(where, "'keys' needs an array of at least one {\"frame\": F, \"camera\": \"POS:TARGET:FOV\"}");
    for (std::size_t i = 0; i < j["keys"].size(); ++i)
        path.keys.push_back(parseKey(j["keys"][i], path.frames, where + ": keys[" + std::to_string(i) + "]"));
    checkIncreasing(path.keys, where, "keys");
    if (j.contains("lights")) {
        if (!j["lights"].is_array()) fail(where, "'lights' needs an array of {\"frame\": F, \"light\": [SPEC, ...]}");
        for (std::size_t i = 0; i < j["lights"].size(); ++i)
            path.lightKeys.push_back(
                parseLights(j["lights"][i], path.frames, where + ": lights[" + std::to_string(i) + "]"));
        checkIncreasing(path.lightKeys, where, "lights");
    }
    // Every frame's view, the keys' and those between them (two keys on either side of their target can
    // pass through it).
    for (int f = 0; f < path.frames; ++f) checkedCamera(path.at(f), Camera{}, where + ": frame " + std::to_string(f));
    return path;
}

CameraPath loadCameraPath(const std::string& file)
{
    std::ifstream in(file);
    if (!in) fail(file, "cannot open the camera path");
    json j;
    try {
        j = json::parse(in);
    } catch (const json::exception& e) {
        fail(file, std::string("malformed JSON: ") + e.what());
    }
    return parseCameraPath(j, file);
}

} // namespace bounce::core
