// GL resources that cannot be had are refused with a ResourceError naming the resource, its size and
// the limit, before GL sees them: nothing is left half-made and no GL error is raised.
#include <gtest/gtest.h>

#include "gl/gl.h"
#include "gl/resource/resource_error.h"
#include "gl/resource/texture.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class ResourceErrorTest : public GlTest {};

int limit(unsigned pname)
{
    GLint v = 0;
    glGetIntegerv(pname, &v);
    return v;
}

TEST_F(ResourceErrorTest, TextureOverTheMaximumSizeNamesItselfAndTheLimit)
{
    const int maxSize = limit(GL_MAX_TEXTURE_SIZE);
    try {
        gl::Texture::create2D("test.huge", GL_RGBA32F, maxSize + 1, 1);
        FAIL() << "expected a ResourceError";
    } catch (const gl::ResourceError& e) {
        EXPECT_EQ(e.label, "test.huge");
        EXPECT_NE(std::string(e.what()).find(std::to_string(maxSize)), std::string::npos) << e.what();
    }
}

// The finding behind it: 1000 point lights asked for 6000 shadow layers.
TEST_F(ResourceErrorTest, ArrayOverTheMaximumLayersNamesTheLimit)
{
    const int maxLayers = limit(GL_MAX_ARRAY_TEXTURE_LAYERS);
    try {
        gl::Texture::create2DArray("shadow.depth", GL_DEPTH_COMPONENT32F, 4, 4, maxLayers + 1);
        FAIL() << "expected a ResourceError";
    } catch (const gl::ResourceError& e) {
        EXPECT_EQ(e.label, "shadow.depth");
        EXPECT_NE(std::string(e.what()).find("array layers"), std::string::npos) << e.what();
    }
    // At the limit it is made (4x4 texels a layer: a few hundred kilobytes).
    EXPECT_NO_THROW(gl::Texture::create2DArray("shadow.depth", GL_DEPTH_COMPONENT32F, 4, 4, maxLayers));
}

} // namespace
} // namespace bounce
