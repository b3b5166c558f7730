// Alpha-masked materials (glTF alphaMode MASK) through core: the mask rule, and the glTF writer and
// reader carrying the mode, the cutoff, baseColorFactor's alpha and the texture's alpha channel.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/cornell.h"
#include "core/gltf_io.h"
#include "io_test_util.h"
#include "tests/alpha_mask_scene.h"

namespace bounce::core {
namespace {

// glTF 3.9.4: rendered opaque where alpha >= alphaCutoff, a hole below it; OPAQUE ignores alpha.
TEST(AlphaMask, CutoffRuleFollowsGltf)
{
    Material m;
    EXPECT_FALSE(m.cutsOut(0.0f)); // opaque: alpha is ignored
    m.alphaMode = AlphaMode::Mask;
    m.alphaCutoff = 0.5f;
    EXPECT_TRUE(m.cutsOut(0.49f));
    EXPECT_FALSE(m.cutsOut(0.5f)); // the cutoff itself is opaque
    EXPECT_FALSE(m.cutsOut(1.0f));
    m.baseAlpha = 0.5f; // baseColorFactor.a multiplies the texture's alpha
    EXPECT_TRUE(m.cutsOut(0.99f));
    EXPECT_FALSE(m.cutsOut(1.0f));
    m.alphaCutoff = 0.0f;
    EXPECT_FALSE(m.cutsOut(0.0f)); // cutoff 0 cuts nothing
}

TEST(AlphaMask, GltfRoundTripKeepsModeCutoffFactorAndTextureAlpha)
{
    const auto dir = test::scratchDir();
    Scene s = makeCornell("cornell-spot");
    testing::addMaskedQuad(s);
    s.materials.back().alphaCutoff = 0.375f;
    s.materials.back().baseAlpha = 0.75f;
    writeGltf(s, (dir / "masked.gltf").string());

    // The file says MASK in glTF's own words (other viewers cut the same holes).
    const nlohmann::json doc = nlohmann::json::parse(std::ifstream(dir / "masked.gltf"));
    const nlohmann::json& written = doc["materials"].back();
    EXPECT_EQ(written["alphaMode"], "MASK");
    EXPECT_DOUBLE_EQ(written["alphaCutoff"].get<double>(), 0.375);
    EXPECT_DOUBLE_EQ(written["pbrMetallicRoughness"]["baseColorFactor"][3].get<double>(), 0.75);
    EXPECT_FALSE(doc["materials"].front().contains("alphaMode")); // opaque materials stay plain

    const Scene back = loadGltf((dir / "masked.gltf").string());
    ASSERT_EQ(back.materials.size(), s.materials.size());
    const Material& m = back.materials.back();
    EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
    EXPECT_EQ(m.alphaCutoff, 0.375f);
    EXPECT_EQ(m.baseAlpha, 0.75f);
    EXPECT_TRUE(m.doubleSided);
    ASSERT_GE(m.baseColorTexture, 0);
    EXPECT_EQ(back.textures[std::size_t(m.baseColorTexture)].rgba8, testing::maskTexture().rgba8); // alpha too
    EXPECT_TRUE(back.hasAlphaMask());
    EXPECT_FALSE(makeCornell("cornell-spot").hasAlphaMask());
    EXPECT_EQ(back.contentHash(), s.contentHash());
}

// References are cached by contentHash: a different mask is a different scene.
TEST(AlphaMask, ContentHashSeesModeAndCutoff)
{
    Scene s = makeCornell("cornell-spot");
    testing::addMaskedQuad(s);
    const std::uint64_t masked = s.contentHash();
    s.materials.back().alphaCutoff = 0.25f;
    EXPECT_NE(s.contentHash(), masked);
    s.materials.back().alphaMode = AlphaMode::Opaque;
    EXPECT_NE(s.contentHash(), masked);
}

// BLEND (translucency) has no model: drawn opaque, with a warning rather than silently.
TEST(AlphaMask, BlendIsReadAsOpaque)
{
    const auto dir = test::scratchDir();
    Scene s = makeCornell("cornell-spot");
    testing::addMaskedQuad(s);
    writeGltf(s, (dir / "blend.gltf").string());
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(dir / "blend.gltf"));
    doc["materials"].back()["alphaMode"] = "BLEND";
    std::ofstream(dir / "blend.gltf") << doc.dump();
    const Scene back = loadGltf((dir / "blend.gltf").string());
    EXPECT_EQ(back.materials.back().alphaMode, AlphaMode::Opaque);
    EXPECT_FALSE(back.hasAlphaMask());
}

} // namespace
} // namespace bounce::core
