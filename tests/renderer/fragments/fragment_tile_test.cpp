#include <algorithm>
#include <map>
#include <random>

#include <gtest/gtest.h>

#include "renderer/fragments/fragment_tile.h"
#include "tests/renderer/fragments/fragment_test_util.h"

namespace clipblur {

namespace {

// A watertight mesh over [0, 8]^2: a 6x6 vertex grid with jittered interior vertices, two triangles per
// cell, all on the plane w.
std::vector<ScreenTriangle> jitteredMesh(std::mt19937_64& rng, const testing::Plane& w, std::uint32_t first) {
    const int n = 6;
    std::uniform_real_distribution<double> jitter(-0.5, 0.5);
    std::vector<glm::dvec2> v;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            glm::dvec2 p(8.0 * i / (n - 1), 8.0 * j / (n - 1));
            if (i > 0 && i < n - 1) p.x += jitter(rng);
            if (j > 0 && j < n - 1) p.y += jitter(rng);
            v.push_back(p);
        }
    }
    std::vector<ScreenTriangle> tris;
    for (int j = 0; j + 1 < n; ++j) {
        for (int i = 0; i + 1 < n; ++i) {
            const glm::dvec2 a = v[j * n + i], b = v[j * n + i + 1], c = v[(j + 1) * n + i + 1], d = v[(j + 1) * n + i];
            tris.push_back(testing::makeTriangle(a, b, c, w, first + std::uint32_t(tris.size())));
            tris.push_back(testing::makeTriangle(a, c, d, w, first + std::uint32_t(tris.size())));
        }
    }
    return tris;
}

}  // namespace

TEST(FragmentTile, WatertightMeshCoversEveryPixelOnceAndHidesTheMeshBehind) {
    std::mt19937_64 rng(8);
    auto front = jitteredMesh(rng, {0.001, 0.002, 0.5}, 0);
    auto back = jitteredMesh(rng, {0.0, 0.0, 0.25}, 1000);
    std::vector<ScreenTriangle> tris = back;
    tris.insert(tris.end(), front.begin(), front.end());
    const PixelBounds rect = PixelBounds::sized(1, 1, 6, 6);
    TileScratch scratch;
    FragmentTile tile;
    resolveTile(tris, rect, {}, scratch, tile);
    ASSERT_EQ(tile.offsets.size(), 37u);
    EXPECT_EQ(tile.rejected_triangles, 0);
    std::map<std::uint32_t, double> by_source;
    for (int y = 1; y < 7; ++y) {
        for (int x = 1; x < 7; ++x) {
            double sum = 0.0;
            for (const Fragment& f : tile.pixel(x, y)) {
                sum += f.area;
                by_source[f.sources[0].source] += f.area;
                EXPECT_LT(f.sources[0].source, 1000u) << "back mesh visible at " << x << "," << y;
            }
            // Mesh triangles share exact edges; the pixel is tiled up to rounding of O(10) coordinates.
            EXPECT_NEAR(sum, 1.0, 1e-12) << x << "," << y;
            EXPECT_NEAR(tile.covered_area[(y - 1) * 6 + (x - 1)], 1.0, 1e-12);
        }
    }
    EXPECT_LT(tile.dropped_area, 1e-10);

    // Per-source areas do not depend on triangle order.
    std::shuffle(tris.begin(), tris.end(), rng);
    FragmentTile again;
    resolveTile(tris, rect, {}, scratch, again);
    std::map<std::uint32_t, double> shuffled;
    for (const Fragment& f : again.fragments) shuffled[f.sources[0].source] += f.area;
    ASSERT_EQ(shuffled.size(), by_source.size());
    for (const auto& [src, area] : by_source) EXPECT_NEAR(shuffled[src], area, 1e-12) << src;
}

TEST(FragmentTile, TriangleAreaIsConservedAcrossTilePixels) {
    const auto t = testing::makeTriangle({2.3, 1.7}, {9.6, 4.1}, {4.4, 8.9}, {0, 0, 1}, 0);
    TileScratch scratch;
    FragmentTile tile;
    resolveTile(std::span(&t, 1), PixelBounds::sized(0, 0, 12, 12), {}, scratch, tile);
    double sum = 0.0;
    for (const Fragment& f : tile.fragments) sum += f.area;
    const double exact = 0.5 * std::abs((9.6 - 2.3) * (8.9 - 1.7) - (4.1 - 1.7) * (4.4 - 2.3));
    EXPECT_NEAR(sum, exact, 1e-12 * exact);
}

TEST(FragmentTile, CountsInvalidTrianglesOnce) {
    std::vector<ScreenTriangle> tris{testing::makeTriangle({0, 0}, {5, 0}, {0, 5}, {0, 0, 1}, 0),
                                     testing::makeTriangle({0, 0}, {5, 0}, {0, 5}, {0, 0, 1}, 1)};
    tris[1].raster[1].x = NAN;
    TileScratch scratch;
    FragmentTile tile;
    resolveTile(tris, PixelBounds::sized(0, 0, 4, 4), {}, scratch, tile);
    EXPECT_EQ(tile.rejected_triangles, 1);
    for (const Fragment& f : tile.fragments) EXPECT_EQ(f.sources[0].source, 0u);
}

}  // namespace clipblur
