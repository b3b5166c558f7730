// What the glTF reader makes of material textures Bounce has no per-texel model for: a
// metallicRoughness texture's mean multiplies the factors (gltf_io.h). Without it, metallicFactor's
// default of 1 turns a textured stone (Crytek Sponza) into a metal that reflects no diffuse light.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/cornell.h"
#include "core/gltf_io.h"
#include "io_test_util.h"
#include "tests/alpha_mask_scene.h"

namespace bounce::core {
namespace {

TEST(GltfMaterials, MetallicRoughnessTextureMeanScalesTheFactors)
{
    const auto dir = test::scratchDir();
    Scene s = makeCornell("cornell-spot");
    testing::addMaskedQuad(s); // its texture, every texel (60, 200, 60, a): blue 60, green 200
    writeGltf(s, (dir / "mr.gltf").string());
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(dir / "mr.gltf"));
    nlohmann::json& pbr = doc["materials"][0]["pbrMetallicRoughness"];
    pbr.erase("metallicFactor"); // glTF's default, 1
    pbr["roughnessFactor"] = 0.5;
    pbr["metallicRoughnessTexture"] = {{"index", 0}};
    std::ofstream(dir / "mr.gltf") << doc.dump();

    const Scene back = loadGltf((dir / "mr.gltf").string());
    EXPECT_NEAR(back.materials[0].metallic, 60.0 / 255.0, 1e-6);
    EXPECT_NEAR(back.materials[0].roughness, 0.5 * 200.0 / 255.0, 1e-6);
    // The other materials keep their factors.
    EXPECT_EQ(back.materials[1].metallic, s.materials[1].metallic);
    EXPECT_EQ(back.materials[1].roughness, s.materials[1].roughness);
}

} // namespace
} // namespace bounce::core
