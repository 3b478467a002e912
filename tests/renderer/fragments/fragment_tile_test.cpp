#include <algorithm>
#include <map>
#include <random>

#include <gtest/gtest.h>

#include "renderer/fragments/fragment_audit.h"
#include "renderer/fragments/fragment_tile.h"
#include "tests/renderer/fragments/fragment_test_util.h"

namespace clipblur {

namespace {

// A watertight mesh over [lo, hi]^2 (default [0, 8]^2): an n x n vertex grid with interior vertices
// jittered by up to `amplitude` px, two triangles per cell, all on the plane w.
std::vector<ScreenTriangle> jitteredMesh(std::mt19937_64& rng, const testing::Plane& w, std::uint32_t first,
                                         double lo = 0.0, double hi = 8.0, int n = 6, double amplitude = 0.5) {
    std::uniform_real_distribution<double> jitter(-amplitude, amplitude);
    std::vector<glm::dvec2> v;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            glm::dvec2 p(lo + (hi - lo) * i / (n - 1), lo + (hi - lo) * j / (n - 1));
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

// One surface cut into unit squares (two triangles each) on a grid offset by `offset`, over [-2, 12]^2:
// what a layer's pixel fragments of one mesh triangle look like once moved to a re-clip's time.
std::vector<ScreenTriangle> squarePieces(const glm::dvec2& offset, const testing::Plane& w, std::uint8_t layer,
                                         float weight, std::uint64_t surface) {
    std::vector<ScreenTriangle> tris;
    for (int j = -2; j < 12; ++j) {
        for (int i = -2; i < 12; ++i) {
            const glm::dvec2 lo = offset + glm::dvec2(i, j);
            for (ScreenTriangle t : testing::makeQuad(lo.x, lo.y, lo.x + 1, lo.y + 1, w,
                                                      std::uint32_t(layer * 1000 + tris.size()), layer, weight)) {
                t.surface = surface;
                tris.push_back(t);
            }
        }
    }
    return tris;
}

std::vector<ScreenTriangle> withoutSurfaces(std::vector<ScreenTriangle> tris) {
    for (ScreenTriangle& t : tris) t.surface = ScreenTriangle::kNoSurface;
    return tris;
}

// A tile resolved with the surface keys (whole pixels kept whole) and without (every pixel clipped).
struct BothWays {
    FragmentTile whole;
    FragmentTile clipped;
};
BothWays resolveBothWays(const std::vector<ScreenTriangle>& tris, const PixelBounds& rect) {
    TileScratch scratch;
    BothWays out;
    resolveTile(tris, rect, {}, scratch, out.whole);
    resolveTile(withoutSurfaces(tris), rect, {}, scratch, out.clipped);
    return out;
}

// Whether every pixel shows each source over the same area in both tiles, to `tolerance` px^2.
bool sameAreas(const FragmentTile& a, const FragmentTile& b, double tolerance) {
    for (int y = a.rect.y0; y < a.rect.y1; ++y) {
        for (int x = a.rect.x0; x < a.rect.x1; ++x) {
            const auto pa = testing::areaBySource({a.pixel(x, y).begin(), a.pixel(x, y).end()});
            const auto pb = testing::areaBySource({b.pixel(x, y).begin(), b.pixel(x, y).end()});
            if (pa.size() != pb.size()) return false;
            for (const auto& [source, area] : pa)
                if (!pb.count(source) || std::abs(pb.at(source) - area) > tolerance) return false;
        }
    }
    return true;
}

}  // namespace

TEST(FragmentTile, PixelWhollyInsideOneSurfaceFromBothLayersIsOneMixedFragment) {
    const testing::Plane w{0.001, -0.002, 0.5};
    std::vector<ScreenTriangle> tris = squarePieces({0.3, 0.6}, w, 0, 0.25f, 7);
    const auto closing = squarePieces({0.75, 0.15}, w, 1, 0.75f, 7);
    tris.insert(tris.end(), closing.begin(), closing.end());
    const PixelBounds rect = PixelBounds::sized(1, 1, 7, 7);
    auto [whole, clipped] = resolveBothWays(tris, rect);
    for (int y = rect.y0; y < rect.y1; ++y) {
        for (int x = rect.x0; x < rect.x1; ++x) {
            const auto pixel = whole.pixel(x, y);
            ASSERT_EQ(pixel.size(), 1u) << x << "," << y;
            const Fragment& f = pixel[0];
            EXPECT_EQ(f.area, 1.0);
            ASSERT_EQ(f.source_count, 2);
            EXPECT_EQ(f.sources[0].layer, 0);
            EXPECT_EQ(f.sources[1].layer, 1);
            EXPECT_DOUBLE_EQ(f.mix(1), 0.75);
            // Clipped against each other, the two grids cut the pixel into up to nine pieces, every one
            // mixed, covering it to rounding of O(10) coordinates.
            double area = 0.0;
            for (const Fragment& g : clipped.pixel(x, y)) {
                area += g.area;
                EXPECT_EQ(g.source_count, 2);
            }
            EXPECT_GT(clipped.pixel(x, y).size(), 1u);
            EXPECT_NEAR(area, 1.0, 1e-12);
        }
    }
    AuditStats audit;
    auditTile(tris, whole, audit);
    EXPECT_EQ(audit.violations, 0) << audit.first_violation;
    EXPECT_EQ(audit.pixels, 49);
}

TEST(FragmentTile, PixelsWithAHoleOrTwoDepthsAreClippedAsBefore) {
    const testing::Plane w{0.001, -0.002, 0.5};
    std::vector<ScreenTriangle> tris = squarePieces({0.3, 0.6}, w, 0, 0.5f, 7);
    // A hole: the closing layer misses one square, so the four pixels it overlaps are covered by one
    // layer only in part.
    std::vector<ScreenTriangle> closing = squarePieces({0.75, 0.15}, w, 1, 0.5f, 7);
    closing.erase(closing.begin() + 2 * (14 * 6 + 6), closing.begin() + 2 * (14 * 6 + 6) + 2);
    tris.insert(tris.end(), closing.begin(), closing.end());
    const PixelBounds rect = PixelBounds::sized(1, 1, 7, 7);
    auto [whole, clipped] = resolveBothWays(tris, rect);
    int single = 0;
    for (const Fragment& f : whole.fragments) single += f.source_count == 1;
    EXPECT_GT(single, 0);  // the hole is seen through to the opening layer alone
    // The hole's square spans [4.75, 5.75] x [4.15, 5.15]: pixels (4..5, 4..5) are clipped as without keys.
    for (int y = 4; y < 6; ++y)
        for (int x = 4; x < 6; ++x) EXPECT_GT(whole.pixel(x, y).size(), 1u) << x << "," << y;
    AuditStats audit;
    auditTile(tris, whole, audit);
    EXPECT_EQ(audit.violations, 0) << audit.first_violation;

    // Planes 1e-5 apart (above the 1e-6 coincidence tolerance) are two surfaces, not one: every pixel is
    // clipped, and shows what it shows without keys (the keys only spare clipping one layer's squares
    // against each other, which share edges: 1e-12 px^2 for pieces of O(10) coordinates).
    std::vector<ScreenTriangle> apart = squarePieces({0.3, 0.6}, w, 0, 0.5f, 7);
    const auto behind = squarePieces({0.75, 0.15}, {w.a, w.b, w.c * (1 - 1e-5)}, 1, 0.5f, 7);
    apart.insert(apart.end(), behind.begin(), behind.end());
    const BothWays two = resolveBothWays(apart, rect);
    EXPECT_TRUE(sameAreas(two.whole, two.clipped, 1e-12));
    for (const Fragment& f : two.whole.fragments) EXPECT_EQ(f.source_count, 1);  // nothing mixed
    for (const Fragment& f : two.whole.fragments) EXPECT_EQ(f.sources[0].layer, 0);  // the nearer layer hides
}

TEST(FragmentTile, SurfaceWhollyInFrontHidesThePiecesBehindItWithoutClipping) {
    const testing::Plane w{0.001, -0.002, 0.5};
    std::vector<ScreenTriangle> tris = squarePieces({0.3, 0.6}, w, 0, 0.5f, 7);
    const auto closing = squarePieces({0.75, 0.15}, w, 1, 0.5f, 7);
    tris.insert(tris.end(), closing.begin(), closing.end());
    // A deep tile's hidden layer: a big triangle of another surface, 1 % farther, inserted first.
    ScreenTriangle hidden = testing::makeTriangle({-5, -5}, {30, -5}, {-5, 30}, {w.a, w.b, w.c * 0.99}, 5000);
    hidden.surface = 8;
    tris.insert(tris.begin(), hidden);
    const PixelBounds rect = PixelBounds::sized(1, 1, 7, 7);
    TileScratch scratch;
    FragmentTile tile;
    resolveTile(tris, rect, {}, scratch, tile);
    for (int y = rect.y0; y < rect.y1; ++y) {
        for (int x = rect.x0; x < rect.x1; ++x) {
            ASSERT_EQ(tile.pixel(x, y).size(), 1u) << x << "," << y;
            EXPECT_EQ(tile.pixel(x, y)[0].source_count, 2);
        }
    }
    AuditStats audit;
    auditTile(tris, tile, audit);
    EXPECT_EQ(audit.violations, 0) << audit.first_violation;

    // The same triangle 1 % nearer is in front: every pixel shows it alone, as the resolver finds it
    // (which starts the square at another corner).
    tris.front() = testing::makeTriangle({-5, -5}, {30, -5}, {-5, 30}, {w.a, w.b, w.c * 1.01}, 5000);
    tris.front().surface = 8;
    FragmentTile clipped;
    resolveTile(tris, rect, {}, scratch, tile);
    resolveTile(withoutSurfaces(tris), rect, {}, scratch, clipped);
    for (int y = rect.y0; y < rect.y1; ++y) {
        for (int x = rect.x0; x < rect.x1; ++x) {
            ASSERT_EQ(tile.pixel(x, y).size(), 1u);
            ASSERT_EQ(clipped.pixel(x, y).size(), 1u);
            const Fragment &f = tile.pixel(x, y)[0], &g = clipped.pixel(x, y)[0];
            EXPECT_EQ(f.sources, g.sources);
            EXPECT_EQ(f.source_count, 1);
            EXPECT_EQ(f.sources[0].source, 5000u);
            EXPECT_NEAR(f.area, g.area, 1e-15);  // px^2: shoelace rounding of a unit square
        }
    }

    // Crossing the surface (nearer at one side of the tile, farther at the other), it is clipped where
    // it crosses and hides or is hidden elsewhere: the audit's independent union and visibility agree.
    tris.front() = testing::makeTriangle({-5, -5}, {30, -5}, {-5, 30}, {w.a + 0.004, w.b, w.c - 0.018}, 5000);
    tris.front().surface = 8;
    resolveTile(tris, rect, {}, scratch, tile);
    audit = AuditStats();
    auditTile(tris, tile, audit);
    EXPECT_EQ(audit.violations, 0) << audit.first_violation;
    int front = 0, whole = 0;
    for (const Fragment& f : tile.fragments) front += f.sources[0].source == 5000u, whole += f.area == 1.0;
    EXPECT_GT(front, 0);
    EXPECT_GT(whole, 0);
}

// Pixels inside one triangle of a surface from each layer are made whole without clipping anything
// (containedPixel); the rest go to the resolver. Either way each pixel shows what clipping every piece
// against every other shows: the same area per source. Seeded meshes of 6 px cells, each triangle its own
// surface, the closing layer the same mesh moved within its plane, under an occluder 1 % nearer over part
// of the tile and a plane that cuts through the mesh.
TEST(FragmentTile, PixelsInsideOneTriangleOfEachLayerMatchClippingEverything) {
    const testing::Plane w{0.001, -0.002, 0.5};
    for (std::uint64_t seed : {3u, 4u, 5u}) {
        std::mt19937_64 rng(seed);
        std::vector<ScreenTriangle> tris = jitteredMesh(rng, w, 0, -4.0, 20.0, 5, 1.5);
        const std::size_t n = tris.size();
        const glm::dvec2 moved(0.37, -0.21);
        for (std::size_t k = 0; k < n; ++k) {
            tris[k].surface = k;
            ScreenTriangle t = tris[k];
            for (glm::dvec2& p : t.raster) p += moved;
            for (int i = 0; i < 3; ++i) t.inv_depth[i] = w(t.raster[i]);
            t.source = std::uint32_t(1000 + k);
            t.layer = 1;
            t.weight = 0.25f;
            tris.push_back(t);
        }
        ScreenTriangle occluder = testing::makeTriangle({2.5, 1.5}, {14.5, 3.5}, {5.5, 9.5}, {w.a, w.b, w.c * 1.01}, 5000);
        occluder.surface = 5000;
        ScreenTriangle cutting = testing::makeTriangle({9, 9}, {17, 10}, {11, 17}, {w.a + 0.004, w.b, w.c - 0.05}, 6000);
        cutting.surface = 6000;
        tris.push_back(occluder);
        tris.push_back(cutting);

        const PixelBounds rect = PixelBounds::sized(0, 0, 16, 16);
        auto [whole, clipped] = resolveBothWays(tris, rect);
        int whole_pixels = 0;
        int one_surface = 0;  // pixels the clipped tile gives wholly to one surface (k and 1000 + k, or another)
        for (int y = rect.y0; y < rect.y1; ++y) {
            for (int x = rect.x0; x < rect.x1; ++x) {
                const auto pixel = whole.pixel(x, y);
                whole_pixels += pixel.size() == 1 && pixel[0].area == 1.0;
                const auto a = testing::areaBySource({pixel.begin(), pixel.end()});
                const auto c = testing::areaBySource({clipped.pixel(x, y).begin(), clipped.pixel(x, y).end()});
                const auto surfaceOf = [](std::uint32_t source) { return source < 2000 ? source % 1000 : source; };
                one_surface += !c.empty() && std::all_of(c.begin(), c.end(), [&](const auto& sa) {
                    return surfaceOf(sa.first) == surfaceOf(c.begin()->first) && std::abs(sa.second - 1.0) < 1e-12;
                });
                ASSERT_EQ(a.size(), c.size()) << seed << ": " << x << "," << y;
                for (const auto& [source, area] : c) {
                    ASSERT_TRUE(a.count(source)) << seed << ": " << x << "," << y << " source " << source;
                    // px^2: clipped pieces of a pixel sum to its area to rounding of O(10) coordinates.
                    EXPECT_NEAR(a.at(source), area, 1e-12) << seed << ": " << x << "," << y;
                }
            }
        }
        // Every pixel one surface covers in front is one fragment, and there are such pixels.
        EXPECT_EQ(whole_pixels, one_surface) << seed;
        EXPECT_GT(one_surface, 0) << seed;
        AuditStats audit;
        auditTile(tris, whole, audit);
        EXPECT_EQ(audit.violations, 0) << seed << ": " << audit.first_violation;
    }
}

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
