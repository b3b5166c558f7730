// The texture atlas of global ray-bundles (core/atlas.h): every triangle's texels inside its chart, charts
// apart by their gutters, the filled border covering every texel a surface touches or a bilinear lookup
// reads, the texel density, the atlas size following the surface area, and the hard cases (a degenerate
// triangle, a density too high for the atlas, NaN density, an empty scene).
#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "core/atlas.h"
#include "core/cornell.h"
#include "core/sampling.h"

namespace bounce {
namespace {

core::AtlasSettings density(float texelsPerMetre)
{
    core::AtlasSettings s;
    s.texelsPerMetre = texelsPerMetre;
    return s;
}

// A unit cube: six quads, twelve triangles, every quad its own chart.
core::Scene cube()
{
    core::Scene s;
    s.materials.emplace_back();
    core::Mesh m;
    const auto quad = [&](glm::vec3 o, glm::vec3 u, glm::vec3 v) {
        const glm::vec3 n = glm::normalize(glm::cross(u, v));
        const auto base = std::uint32_t(m.positions.size());
        for (const glm::vec3& p : {o, o + u, o + u + v, o + v}) {
            m.positions.push_back(p);
            m.normals.push_back(n);
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
    };
    quad({0, 0, 0}, {0, 1, 0}, {1, 0, 0});
    quad({0, 0, 1}, {1, 0, 0}, {0, 1, 0});
    quad({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
    quad({1, 0, 0}, {0, 1, 0}, {0, 0, 1});
    quad({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
    quad({0, 1, 0}, {0, 0, 1}, {1, 0, 0});
    s.meshes.push_back(m);
    return s;
}

void expectValidAtlas(const core::Atlas& a)
{
    // Charts inside the atlas and apart, gutters included.
    for (std::size_t c = 0; c < a.charts.size(); ++c) {
        const core::AtlasChart& ch = a.charts[c];
        ASSERT_GE(ch.origin.x, 0);
        ASSERT_GE(ch.origin.y, 0);
        ASSERT_LE(ch.origin.x + ch.size.x, a.width);
        ASSERT_LE(ch.origin.y + ch.size.y, a.height);
    }
    std::vector<int> owner(std::size_t(a.width) * std::size_t(a.height), -1);
    for (std::size_t c = 0; c < a.charts.size(); ++c) {
        const core::AtlasChart& ch = a.charts[c];
        for (int y = ch.origin.y; y < ch.origin.y + ch.size.y; ++y)
            for (int x = ch.origin.x; x < ch.origin.x + ch.size.x; ++x) {
                int& o = owner[std::size_t(y) * a.width + x];
                ASSERT_EQ(o, -1) << "charts " << o << " and " << c << " overlap at texel " << x << "," << y;
                o = int(c);
            }
    }
    // Every triangle's touched texels inside its chart's interior; every texel it fills (its border for
    // llvmpipe's missing conservative rasterisation) inside its chart's rectangle.
    for (std::size_t t = 0; t < a.triangleCount(); ++t) {
        const std::uint32_t c = a.triangleChart[t];
        const glm::ivec4 in = a.interior(c);
        for (const glm::ivec2& p : core::touchedTexels(a.corners[t])) {
            ASSERT_TRUE(p.x >= in.x && p.y >= in.y && p.x < in.z && p.y < in.w)
                << "triangle " << t << " touches texel " << p.x << "," << p.y << " outside its chart's interior";
        }
        const glm::vec4 q = core::fillQuad(a.corners[t]);
        for (int y = int(std::floor(q.y)); y <= int(std::floor(q.w)); ++y)
            for (int x = int(std::floor(q.x)); x <= int(std::floor(q.z)); ++x)
                if (core::fillsTexel(a.corners[t], x, y)) {
                    ASSERT_TRUE(x >= 0 && y >= 0 && x < a.width && y < a.height);
                    ASSERT_EQ(owner[std::size_t(y) * a.width + x], int(c))
                        << "triangle " << t << " fills texel " << x << "," << y << " outside its chart";
                    // At least one gutter texel stays empty between charts: filled texels keep one texel
                    // away from the rectangle's edge.
                    ASSERT_TRUE(x > in.x - a.gutter && y > in.y - a.gutter && x < in.z + a.gutter - 1 &&
                                y < in.w + a.gutter - 1);
                }
    }
}

TEST(Atlas, CornellVariantsAreValid)
{
    for (const char* name : {"cornell-area", "cornell-slats", "cornell-glossy"}) {
        SCOPED_TRACE(name);
        const core::Scene s = core::makeCornell(name);
        for (float d : {8.0f, 64.0f, 200.0f}) {
            const core::Atlas a = core::buildAtlas(s, density(d));
            EXPECT_EQ(a.triangleCount(), s.triangleCount());
            expectValidAtlas(a);
        }
    }
}

TEST(Atlas, RegionGrowingMakesOneChartPerPlanarFace)
{
    const core::Atlas a = core::buildAtlas(cube(), density(16.0f));
    EXPECT_EQ(a.charts.size(), 6u); // two triangles each, the crease of 90 degrees stops growth
    for (const core::AtlasChart& c : a.charts) EXPECT_EQ(c.triangleCount, 2u);
    // The Cornell box: the floor's two triangles share one chart; the red wall's quad is not planar (a
    // vertex 3.2 mm off) but far within the angle, so it is one chart too.
    const core::Scene s = core::makeCornell("cornell-area");
    const core::Atlas b = core::buildAtlas(s, density(32.0f));
    EXPECT_EQ(b.triangleChart[0], b.triangleChart[1]); // floor
    EXPECT_EQ(b.triangleChart[8], b.triangleChart[9]); // red wall
    EXPECT_NE(b.triangleChart[0], b.triangleChart[2]); // floor and ceiling
}

TEST(Atlas, TexelDensity)
{
    // A triangle covers area x density^2 x cos(its normal, its chart's normal) texels.
    const core::Scene s = core::makeCornell("cornell-area");
    const float d = 50.0f;
    const core::Atlas a = core::buildAtlas(s, density(d));
    std::size_t t = 0;
    for (const core::Mesh& m : s.meshes)
        for (std::size_t i = 0; i < m.indices.size(); i += 3, ++t) {
            const glm::vec3 p0 = m.positions[m.indices[i]], p1 = m.positions[m.indices[i + 1]],
                            p2 = m.positions[m.indices[i + 2]];
            const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
            const double world = 0.5 * glm::length(n);
            const double cosine = std::abs(glm::dot(glm::normalize(n), a.charts[a.triangleChart[t]].normal));
            const auto& c = a.corners[t];
            const double texels =
                0.5 * std::abs((c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[1].y - c[0].y) * (c[2].x - c[0].x));
            EXPECT_NEAR(texels, world * d * d * cosine, 1e-3 * world * d * d + 1e-3) << "triangle " << t;
        }
}

TEST(Atlas, FilledBorderCoversEveryTouchedTexelAndEveryBilinearLookup)
{
    const core::Scene s = core::makeCornell("cornell-slats");
    const core::Atlas a = core::buildAtlas(s, density(40.0f));
    core::Pcg32 rng(7);
    for (std::size_t t = 0; t < a.triangleCount(); ++t) {
        const auto& c = a.corners[t];
        for (const glm::ivec2& p : core::touchedTexels(c))
            ASSERT_TRUE(core::fillsTexel(c, p.x, p.y)) << "triangle " << t << ", texel " << p.x << "," << p.y;
        for (int k = 0; k < 64; ++k) {
            const glm::vec2 b = core::sampleUniformTriangle(rng.next2());
            const glm::vec2 q = b.x * c[0] + b.y * c[1] + (1.0f - b.x - b.y) * c[2];
            const glm::ivec2 base = glm::ivec2(glm::floor(q - 0.5f));
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx)
                    ASSERT_TRUE(core::fillsTexel(c, base.x + dx, base.y + dy))
                        << "a bilinear lookup inside triangle " << t << " reads an empty texel";
        }
    }
}

TEST(Atlas, SizeFollowsTheSurfaceArea)
{
    // The density for N texels gives charts whose interiors hold about N texels (more: every chart rounds
    // up to whole texels), and doubling N doubles them.
    const core::Scene s = core::makeCornell("cornell-area");
    const auto interiorTexels = [&](double n) {
        core::AtlasSettings st;
        st.texelsPerMetre = core::texelsPerMetreFor(s, n);
        const core::Atlas a = core::buildAtlas(s, st);
        double sum = 0.0;
        for (std::uint32_t c = 0; c < a.charts.size(); ++c) {
            const glm::ivec4 in = a.interior(c);
            sum += double(in.z - in.x) * double(in.w - in.y);
        }
        return std::pair(sum, a);
    };
    const auto [small, a1] = interiorTexels(16384.0);
    const auto [large, a2] = interiorTexels(65536.0);
    EXPECT_GT(small, 16384.0);
    EXPECT_LT(small, 1.6 * 16384.0);
    EXPECT_GT(large, 65536.0);
    EXPECT_LT(large, 1.3 * 65536.0);
    EXPECT_GT(double(a2.width) * a2.height, 3.0 * double(a1.width) * a1.height);
    // About square.
    EXPECT_LT(std::max(a2.width, a2.height), 2 * std::min(a2.width, a2.height));
}

TEST(Atlas, HardCases)
{
    // A degenerate triangle (all corners on a line) gets texels like any other.
    core::Scene s = cube();
    core::Mesh sliver;
    sliver.positions = {{2, 0, 0}, {3, 0, 0}, {4, 0, 0}};
    sliver.normals.assign(3, {0, 1, 0});
    sliver.indices = {0, 1, 2};
    s.meshes.push_back(sliver);
    const core::Atlas a = core::buildAtlas(s, density(10.0f));
    expectValidAtlas(a);
    EXPECT_EQ(a.triangleCount(), 13u);
    // A density that needs an atlas beyond the maximum, NaN and zero densities, and a scene without
    // triangles are refused with a message.
    core::AtlasSettings huge = density(1e6f);
    huge.maxSize = 4096;
    EXPECT_THROW(core::buildAtlas(cube(), huge), core::AtlasError);
    EXPECT_THROW(core::buildAtlas(cube(), density(std::nanf(""))), core::AtlasError);
    EXPECT_THROW(core::buildAtlas(cube(), density(0.0f)), core::AtlasError);
    EXPECT_THROW(core::buildAtlas(core::Scene{}, density(10.0f)), core::AtlasError);
    core::AtlasSettings thin = density(10.0f);
    thin.gutter = 1;
    EXPECT_THROW(core::buildAtlas(cube(), thin), core::AtlasError);
}

} // namespace
} // namespace bounce
