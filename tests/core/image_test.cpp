// EXR / PFM / PNG input and output: bit-exact float round trips, tone mapping, atomic writes, errors.
#include "core/image.h"

#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <tinyexr.h>

#include "io_test_util.h"

namespace bounce::core {
namespace {

using test::fs::path;

// Values that a lossy or rounding writer would change: tiny, huge, negative, denormal, non-round.
Image testPattern(int w, int h)
{
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.set(x, y, {float(x) * 0.1234567f + 1e-7f, float(y) * 3.3333333e4f, -float(x * y) / 7.0f});
    img.set(0, 0, {std::numeric_limits<float>::denorm_min(), 65504.0f, 1e30f});
    return img;
}

void expectBitExact(const Image& a, const Image& b)
{
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_EQ(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)));
}

bool hasTempFiles(const path& dir)
{
    for (const auto& e : test::fs::directory_iterator(dir))
        if (e.path().filename().string().find(".tmp-") != std::string::npos) return true;
    return false;
}

TEST(ImageIo, ExrFloatRoundTripIsBitExact)
{
    const path dir = test::scratchDir();
    const Image img = testPattern(37, 19); // odd sizes: no row or tile padding hides a bug
    writeExr((dir / "a.exr").string(), img);
    expectBitExact(img, readImage((dir / "a.exr").string()));
}

TEST(ImageIo, ExrRowZeroIsTop)
{
    const path dir = test::scratchDir();
    Image img(2, 3);
    img.set(1, 0, {1.0f, 2.0f, 3.0f});
    writeImage((dir / "top.exr").string(), img);
    const Image back = readImage((dir / "top.exr").string());
    EXPECT_EQ(back.at(1, 0), glm::vec3(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(back.at(1, 2), glm::vec3(0.0f));
}

TEST(ImageIo, ReadsHalfRgbaExr)
{
    // A half-float RGBA file as other tools write them, made with tinyexr directly.
    const path dir = test::scratchDir();
    const int w = 4, h = 2;
    std::vector<std::uint16_t> planes[4]; // A, B, G, R in half
    const std::uint16_t halfOne = 0x3C00, halfTwo = 0x4000, halfHalf = 0x3800;
    for (auto& p : planes) p.assign(std::size_t(w * h), 0);
    for (int i = 0; i < w * h; ++i) {
        planes[0][i] = halfOne;
        planes[1][i] = halfHalf;
        planes[2][i] = halfOne;
        planes[3][i] = halfTwo;
    }
    unsigned char* ptrs[4];
    for (int c = 0; c < 4; ++c) ptrs[c] = reinterpret_cast<unsigned char*>(planes[c].data());
    EXRImage image;
    InitEXRImage(&image);
    image.images = ptrs;
    image.width = w;
    image.height = h;
    image.num_channels = 4;
    EXRHeader header;
    InitEXRHeader(&header);
    EXRChannelInfo channels[4] = {};
    int types[4] = {TINYEXR_PIXELTYPE_HALF, TINYEXR_PIXELTYPE_HALF, TINYEXR_PIXELTYPE_HALF, TINYEXR_PIXELTYPE_HALF};
    const char* names[4] = {"A", "B", "G", "R"};
    for (int c = 0; c < 4; ++c) std::strcpy(channels[c].name, names[c]);
    header.num_channels = 4;
    header.channels = channels;
    header.pixel_types = types;
    header.requested_pixel_types = types;
    header.compression_type = TINYEXR_COMPRESSIONTYPE_NONE;
    const char* err = nullptr;
    ASSERT_EQ(TINYEXR_SUCCESS, SaveEXRImageToFile(&image, &header, (dir / "half.exr").string().c_str(), &err));

    const Image back = readImage((dir / "half.exr").string());
    ASSERT_EQ(back.width, w);
    ASSERT_EQ(back.height, h);
    EXPECT_EQ(back.at(3, 1), glm::vec3(2.0f, 1.0f, 0.5f));
}

TEST(ImageIo, PfmRoundTripIsBitExact)
{
    const path dir = test::scratchDir();
    const Image img = testPattern(5, 3);
    writeImage((dir / "a.pfm").string(), img);
    expectBitExact(img, readImage((dir / "a.pfm").string()));
}

TEST(ImageIo, ReadsGreyPfmBottomRowFirst)
{
    const path dir = test::scratchDir();
    const float values[2] = {0.25f, 4.0f}; // one column, two rows: the file stores the bottom row first
    std::string bytes = "Pf\n1 2\n-1.0\n";
    bytes.append(reinterpret_cast<const char*>(values), sizeof values);
    test::writeFile(dir / "grey.pfm", bytes);
    const Image img = readImage((dir / "grey.pfm").string());
    ASSERT_EQ(img.width, 1);
    ASSERT_EQ(img.height, 2);
    EXPECT_EQ(img.at(0, 0), glm::vec3(4.0f));
    EXPECT_EQ(img.at(0, 1), glm::vec3(0.25f));
}

TEST(ImageIo, PngIsToneMappedAndSrgbEncoded)
{
    const path dir = test::scratchDir();
    Image img(4, 1);
    img.set(0, 0, {0.0f, 0.5f, 1.0f});           // black, mid grey, white
    img.set(1, 0, {2.0f, -1.0f, std::nanf("")}); // clamped above, below, NaN to black
    img.set(2, 0, {0.25f, 0.25f, 0.25f});        // x 2^1 exposure -> 0.5
    img.set(3, 0, {0.001f, 0.001f, 0.001f});     // x 2 = 0.002: linear segment of sRGB
    writePng((dir / "a.png").string(), img, 1.0f);

    const std::string bytes = test::readFile(dir / "a.png");
    int w = 0, h = 0, n = 0;
    unsigned char* px =
        stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &w, &h, &n, 3);
    ASSERT_NE(px, nullptr);
    ASSERT_EQ(w, 4);
    ASSERT_EQ(h, 1);
    // sRGB(0.5 x 2) = 1 -> 255; sRGB(0.5) = 0.7354 -> 188; sRGB(0.002) = 12.92 x 0.002 = 0.0258 -> 7.
    const int expected[12] = {0, 255, 255, 255, 0, 0, 188, 188, 188, 7, 7, 7};
    for (int i = 0; i < 12; ++i) EXPECT_EQ(int(px[i]), expected[i]) << "byte " << i;
    stbi_image_free(px);
}

TEST(ImageIo, WritesLeaveNoTemporaryFiles)
{
    const path dir = test::scratchDir();
    const Image img = testPattern(8, 8);
    writeImage((dir / "a.exr").string(), img);
    writeImage((dir / "a.png").string(), img);
    writeImage((dir / "a.pfm").string(), img);
    writeImage((dir / "a.exr").string(), img); // overwriting goes through a temporary too
    writeFileAtomic((dir / "raw.bin").string(), "bytes");
    EXPECT_EQ(test::readFile(dir / "raw.bin"), "bytes");
    EXPECT_FALSE(hasTempFiles(dir));
}

TEST(ImageIo, FailedWriteThrowsAndLeavesNothing)
{
    const path dir = test::scratchDir();
    const std::string target = (dir / "no-such-folder" / "a.exr").string();
    try {
        writeExr(target, testPattern(2, 2));
        FAIL() << "expected ImageError";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find("a.exr"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(hasTempFiles(dir));
}

// A set of files appears together or not at all: a set whose last file cannot be written leaves neither
// the files before it nor any temporary behind.
TEST(ImageIo, FileSetIsAllOrNothing)
{
    const path dir = test::scratchDir();
    FileSet ok;
    ok.addImage((dir / "a.exr").string(), testPattern(2, 2));
    ok.add((dir / "a.json").string(), "{}");
    ok.commit();
    EXPECT_TRUE(std::filesystem::exists(dir / "a.exr"));
    EXPECT_EQ(test::readFile(dir / "a.json"), "{}");

    FileSet broken;
    broken.addImage((dir / "b.exr").string(), testPattern(2, 2));
    broken.addImage((dir / "b.png").string(), testPattern(2, 2));
    broken.add((dir / "no-such-folder" / "b.json").string(), "{}");
    EXPECT_THROW(broken.commit(), ImageError);
    EXPECT_FALSE(std::filesystem::exists(dir / "b.exr"));
    EXPECT_FALSE(std::filesystem::exists(dir / "b.png"));
    EXPECT_FALSE(hasTempFiles(dir));
}

// An output that cannot be written is found before any work: a folder in its place, or a folder that
// cannot be made because a file has its name.
TEST(ImageIo, CheckOutputPathRefusesWhatCannotBeWritten)
{
    const path dir = test::scratchDir();
    std::filesystem::create_directories(dir / "folder.exr");
    EXPECT_THROW(checkOutputPath((dir / "folder.exr").string()), ImageError);
    test::writeFile(dir / "file", "x");
    EXPECT_THROW(checkOutputPath((dir / "file" / "a.exr").string()), ImageError);
    EXPECT_NO_THROW(checkOutputPath((dir / "new" / "a.exr").string()));
    EXPECT_TRUE(std::filesystem::is_directory(dir / "new"));
    EXPECT_FALSE(std::filesystem::exists(dir / "new" / "a.exr")) << "the check writes nothing";
    EXPECT_FALSE(hasTempFiles(dir / "new"));
}

TEST(ImageIo, UnknownExtensionThrows)
{
    const path dir = test::scratchDir();
    try {
        writeImage((dir / "a.bmp").string(), testPattern(2, 2));
        FAIL() << "expected ImageError";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find("a.bmp"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("extension"), std::string::npos);
    }
    EXPECT_THROW(readImage((dir / "a.tga").string()), ImageError);
    EXPECT_FALSE(test::fs::exists(dir / "a.bmp"));
}

TEST(ImageIo, BadFilesThrowImageError)
{
    const path dir = test::scratchDir();
    test::writeFile(dir / "junk.exr", "not an exr at all");
    test::writeFile(dir / "short.pfm", "PF\n4 4\n-1.0\n0123");
    test::writeFile(dir / "huge.pfm", "PF\n1000000 1000000\n-1.0\n");
    for (const char* name : {"junk.exr", "short.pfm", "huge.pfm", "missing.exr"}) {
        try {
            readImage((dir / name).string());
            ADD_FAILURE() << name << ": expected ImageError";
        } catch (const ImageError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    }
}

TEST(ImageIo, EmptyImageIsNotWritten)
{
    const path dir = test::scratchDir();
    EXPECT_THROW(writeExr((dir / "e.exr").string(), Image{}), ImageError);
    EXPECT_THROW(writePng((dir / "e.png").string(), Image{}), ImageError);
}

} // namespace
} // namespace bounce::core
