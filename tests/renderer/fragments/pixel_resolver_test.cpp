#include <algorithm>
#include <numeric>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "renderer/fragments/pixel_resolver.h"
#include "renderer/geometry/convex_polygon.h"
#include "tests/renderer/fragments/fragment_test_util.h"

namespace clipblur {

using testing::Plane;

namespace {

std::vector<Fragment> resolvePixel(int px, int py, const std::vector<ScreenTriangle>& tris,
                                   PixelResolver& r) {
    r.reset(px, py);
    for (const ScreenTriangle& t : tris) r.insert(t);
    return r.fragments();
}

ConvexPolygon toPolygon(const Fragment& f) {
    ConvexPolygon p;
    for (int i = 0; i < f.vertex_count; ++i) p.push(f.vertices[i]);
    return p;
}

// Invariants every resolved pixel must satisfy: inside the pixel, positive areas that match the
// vertices, pairwise disjoint.
void checkInvariants(int px, int py, const std::vector<Fragment>& frags) {
    for (std::size_t i = 0; i < frags.size(); ++i) {
        const Fragment& f = frags[i];
        ASSERT_GE(f.vertex_count, 3);
        ASSERT_LE(f.vertex_count, kMaxStoredVertices);
        for (int k = 0; k < f.vertex_count; ++k) {
            // Crossing points are interpolated between in-pixel vertices: at most an ulp outside.
            EXPECT_GE(f.vertices[k].x, px - 1e-12);
            EXPECT_LE(f.vertices[k].x, px + 1 + 1e-12);
            EXPECT_GE(f.vertices[k].y, py - 1e-12);
            EXPECT_LE(f.vertices[k].y, py + 1 + 1e-12);
        }
        EXPECT_GT(f.area, 0.0);
        EXPECT_NEAR(toPolygon(f).area(), f.area, 1e-12);
        for (std::size_t j = i + 1; j < frags.size(); ++j) {
            ConvexPolygon both;
            intersect(toPolygon(f), toPolygon(frags[j]), both);
            // Shared edges are computed once; overlap is rounding of O(1) coordinates only.
            EXPECT_LT(both.degenerate() ? 0.0 : std::abs(both.area()), 1e-12) << i << " vs " << j;
        }
    }
}

}  // namespace

TEST(PixelResolver, SingleTriangleCoverage) {
    PixelResolver r;
    const auto frags = resolvePixel(10, 20, {testing::makeTriangle({10, 20}, {14, 20}, {10, 24}, {0, 0, 1}, 5)}, r);
    ASSERT_EQ(frags.size(), 1u);
    EXPECT_EQ(frags[0].sources[0].source, 5u);
    EXPECT_EQ(r.coveredArea(), 1.0);
    r.reset(12, 21);
    r.insert(testing::makeTriangle({10, 20}, {14, 20}, {10, 24}, {0, 0, 1}, 5));
    EXPECT_EQ(r.coveredArea(), 0.5);
}

TEST(PixelResolver, FrontQuadWinsWithExactAreas) {
    // Front quad (1/z = 1) over a back quad (1/z = 0.5); inserted back first and front first.
    auto front = testing::makeQuad(100.25, 50.3, 101.75, 51.6, {0, 0, 1.0}, 0);
    auto back = testing::makeQuad(100.5, 50.1, 102.5, 52.2, {0, 0, 0.5}, 2);
    for (int order = 0; order < 2; ++order) {
        std::vector<ScreenTriangle> tris = order == 0 ? back : front;
        for (const auto& t : (order == 0 ? front : back)) tris.push_back(t);
        PixelResolver r;
        for (int py = 50; py < 53; ++py) {
            for (int px = 100; px < 103; ++px) {
                const auto frags = resolvePixel(px, py, tris, r);
                checkInvariants(px, py, frags);
                auto by = testing::areaBySource(frags);
                const double f = testing::rectOverlap(px, py, px + 1, py + 1, 100.25, 50.3, 101.75, 51.6);
                const double b = testing::rectOverlap(px, py, px + 1, py + 1, 100.5, 50.1, 102.5, 52.2);
                const double fb = testing::rectOverlap(std::max<double>(px, 100.5), std::max<double>(py, 50.3),
                                                       std::min<double>(px + 1, 101.75),
                                                       std::min<double>(py + 1, 51.6), 100.5, 50.1, 102.5, 52.2);
                // Coordinates ~100 px carry 1.4e-14 px of rounding per vertex: 1e-12 px^2 is ample.
                EXPECT_NEAR(by[0] + by[1], f, 1e-12) << px << "," << py;
                EXPECT_NEAR(by[2] + by[3], b - fb, 1e-12) << px << "," << py;
                EXPECT_NEAR(r.coveredArea(), f + b - fb, 1e-12);
            }
        }
    }
}

TEST(PixelResolver, InterpenetratingQuadsSplitWhereDepthsAreEqual) {
    // Both quads span the same square; d = wA - wB = -0.15 + 0.15x + 0.07y vanishes on a slanted line.
    const Plane wa{0.1, 0.05, 1.0};
    const Plane wb{-0.05, -0.02, 1.15};
    auto tris = testing::makeQuad(0.3, 0.2, 3.7, 3.9, wa, 0);
    for (const auto& t : testing::makeQuad(0.3, 0.2, 3.7, 3.9, wb, 2)) tris.push_back(t);
    PixelResolver r;
    for (int py = 0; py < 4; ++py) {
        for (int px = 0; px < 4; ++px) {
            const auto frags = resolvePixel(px, py, tris, r);
            checkInvariants(px, py, frags);
            auto by = testing::areaBySource(frags);
            std::vector<testing::HalfPlane> hs = testing::pixelConstraints({px, py});
            testing::appendPolygon({{0.3, 0.2}, {3.7, 0.2}, {3.7, 3.9}, {0.3, 3.9}}, hs);
            const double quad = testing::halfPlaneArea(hs);
            const double n = std::hypot(0.15, 0.07);
            hs.push_back({0.15 / n, 0.07 / n, -0.15 / n});  // A nearer: d > 0
            const double a_visible = testing::halfPlaneArea(hs);
            EXPECT_NEAR(by[0] + by[1], a_visible, 1e-9) << px << "," << py;
            EXPECT_NEAR(by[2] + by[3], quad - a_visible, 1e-9) << px << "," << py;
        }
    }
}

TEST(PixelResolver, CoincidentLayersMixWithoutDoubleCounting) {
    const Plane w{0.01, 0.02, 0.5};
    // The frame-1 copy carries a 1e-9 relative depth error, well inside the 1e-6 coincidence tolerance.
    const Plane w1{0.01 * (1 + 1e-9), 0.02 * (1 + 1e-9), 0.5 * (1 + 1e-9)};
    auto a = testing::makeQuad(0.2, 0.1, 2.6, 1.9, w, 0, 0, 0.3f);
    auto b = testing::makeQuad(0.5, 0.4, 3.0, 2.2, w1, 10, 1, 0.7f);
    for (int order = 0; order < 2; ++order) {
        std::vector<ScreenTriangle> tris = order == 0 ? a : b;
        for (const auto& t : (order == 0 ? b : a)) tris.push_back(t);
        PixelResolver r;
        for (int py = 0; py < 3; ++py) {
            for (int px = 0; px < 3; ++px) {
                const auto frags = resolvePixel(px, py, tris, r);
                checkInvariants(px, py, frags);
                const double ra = testing::rectOverlap(px, py, px + 1, py + 1, 0.2, 0.1, 2.6, 1.9);
                const double rb = testing::rectOverlap(px, py, px + 1, py + 1, 0.5, 0.4, 3.0, 2.2);
                const double rab = testing::rectOverlap(std::max<double>(px, 0.5), std::max<double>(py, 0.4),
                                                        std::min<double>(px + 1, 2.6), std::min<double>(py + 1, 1.9),
                                                        0.2, 0.1, 2.6, 1.9);
                double mixed = 0.0;
                for (const Fragment& f : frags) {
                    if (f.source_count != 2) continue;
                    mixed += f.area;
                    EXPECT_EQ(f.sources[0].layer, 0);
                    EXPECT_EQ(f.sources[1].layer, 1);
                    EXPECT_LT(f.sources[0].source, 10u);
                    EXPECT_GE(f.sources[1].source, 10u);
                    EXPECT_NEAR(f.mix(0), 0.3, 1e-7);  // weights are floats
                    EXPECT_NEAR(f.mix(1), 0.7, 1e-7);
                }
                EXPECT_NEAR(mixed, rab, 1e-12) << px << "," << py;
                EXPECT_NEAR(r.coveredArea(), ra + rb - rab, 1e-12) << px << "," << py;
            }
        }
    }
}

TEST(PixelResolver, SameLayerZFightingPicksLowerSourceInAnyOrder) {
    const Plane w{0, 0, 0.25};
    const auto t7 = testing::makeTriangle({0, 0}, {1, 0}, {0, 1}, w, 7);
    const auto t3 = testing::makeTriangle({0, 0}, {1, 0}, {1, 1}, w, 3);
    PixelResolver r;
    for (const auto& tris : {std::vector{t7, t3}, std::vector{t3, t7}}) {
        const auto frags = resolvePixel(0, 0, tris, r);
        auto by = testing::areaBySource(frags);
        EXPECT_NEAR(by[3], 0.5, 1e-15);
        EXPECT_NEAR(by[7], 0.25, 1e-15);  // only the part not under source 3
        for (const Fragment& f : frags) EXPECT_EQ(f.source_count, 1);
    }
}

TEST(PixelResolver, SliverInFrontSurvivesWithItsArea) {
    const Plane back{0, 0, 0.1};
    const Plane front{0, 0, 1.0};
    std::vector<ScreenTriangle> tris = testing::makeQuad(40, 30, 41, 31, back, 0);
    tris.push_back(testing::makeTriangle({40.1, 30.5}, {40.9, 30.5}, {40.5, 30.5 + 1e-9}, front, 9));
    PixelResolver r;
    const auto frags = resolvePixel(40, 30, tris, r);
    auto by = testing::areaBySource(frags);
    const double sliver = 0.5 * 0.8 * ((30.5 + 1e-9) - 30.5);
    // Absolute bound: vertices near 30 px are rounded to 2^-48 px each.
    EXPECT_NEAR(by[9], sliver, 1e-13);
    EXPECT_NEAR(by[0] + by[1] + by[9], 1.0, 1e-13);
}

TEST(PixelResolver, RejectsInvalidTriangles) {
    PixelResolver r;
    r.reset(0, 0);
    auto t = testing::makeTriangle({0, 0}, {1, 0}, {0, 1}, {0, 0, 1}, 0);
    t.inv_depth[0] = NAN;
    r.insert(t);
    t.inv_depth[0] = -1.0;
    r.insert(t);
    EXPECT_EQ(r.rejectedTriangles(), 2);
    EXPECT_TRUE(r.fragments().empty());
    t.inv_depth[0] = 1.0;
    t.layer = 2;
    EXPECT_THROW(r.insert(t), std::invalid_argument);
}

namespace {

// Affine 1/z through three (raster, w) samples, solved independently of the kernel.
Plane planeOf(const ScreenTriangle& t) {
    const glm::dmat3 m(glm::dvec3(t.raster[0].x, t.raster[1].x, t.raster[2].x),
                       glm::dvec3(t.raster[0].y, t.raster[1].y, t.raster[2].y), glm::dvec3(1.0));
    const glm::dvec3 abc = glm::inverse(m) * glm::dvec3(t.inv_depth[0], t.inv_depth[1], t.inv_depth[2]);
    return {abc.x, abc.y, abc.z};
}

// Visible area of triangle i in the pixel by inclusion-exclusion over the sets of triangles in front of it:
// |B_i| - sum |B_i ∩ F_j| + sum |B_i ∩ F_j ∩ F_k| - ..., with B_i = pixel ∩ T_i and F_j = T_j ∩ {w_j > w_i},
// every term a convex region measured by the half-plane oracle.
double visibleAreaOracle(const std::vector<ScreenTriangle>& tris, std::size_t i, const glm::dvec2& pixel) {
    std::vector<testing::HalfPlane> base = testing::pixelConstraints(pixel);
    testing::appendPolygon(testing::ccw(tris[i]), base);
    const Plane wi = planeOf(tris[i]);
    std::vector<std::vector<testing::HalfPlane>> front;
    for (std::size_t j = 0; j < tris.size(); ++j) {
        if (j == i) continue;
        std::vector<testing::HalfPlane> f;
        testing::appendPolygon(testing::ccw(tris[j]), f);
        const Plane wj = planeOf(tris[j]);
        const double a = wj.a - wi.a, b = wj.b - wi.b, c = wj.c - wi.c, n = std::hypot(a, b);
        f.push_back({a / n, b / n, c / n});
        front.push_back(f);
    }
    double total = 0.0;
    for (unsigned mask = 0; mask < (1u << front.size()); ++mask) {
        std::vector<testing::HalfPlane> hs = base;
        int bits = 0;
        for (std::size_t j = 0; j < front.size(); ++j) {
            if (mask & (1u << j)) {
                hs.insert(hs.end(), front[j].begin(), front[j].end());
                ++bits;
            }
        }
        total += (bits % 2 ? -1.0 : 1.0) * testing::halfPlaneArea(hs);
    }
    return total;
}

}  // namespace

TEST(PixelResolver, RandomScenesMatchInclusionExclusionOracleInAnyOrder) {
    std::mt19937_64 rng(2004);
    std::uniform_real_distribution<double> pos(-0.6, 1.6);
    std::uniform_real_distribution<double> depth(0.2, 1.0);
    const glm::dvec2 pixel(7, 3);
    PixelResolver r;
    for (int scene = 0; scene < 300; ++scene) {
        std::vector<ScreenTriangle> tris;
        const int n = 2 + scene % 4;
        for (int k = 0; k < n; ++k) {
            ScreenTriangle t;
            for (int v = 0; v < 3; ++v) {
                t.raster[v] = pixel + glm::dvec2(pos(rng), pos(rng));
                t.inv_depth[v] = depth(rng);
            }
            t.source = std::uint32_t(k);
            tris.push_back(t);
        }
        std::vector<double> expected(n);
        double union_area = 0.0;
        for (int k = 0; k < n; ++k) union_area += expected[k] = visibleAreaOracle(tris, k, pixel);

        std::vector<int> order(n);
        std::iota(order.begin(), order.end(), 0);
        for (int perm = 0; perm < 4; ++perm) {
            std::vector<ScreenTriangle> shuffled;
            for (int k : order) shuffled.push_back(tris[k]);
            const auto frags = resolvePixel(int(pixel.x), int(pixel.y), shuffled, r);
            checkInvariants(int(pixel.x), int(pixel.y), frags);
            auto by = testing::areaBySource(frags);
            // Both sides are sums of O(10) convex areas of O(1) coordinates (~1e-15 each); the oracle's
            // crossings of nearly parallel lines are the weakest link, hence 1e-9.
            for (int k = 0; k < n; ++k) ASSERT_NEAR(by[k], expected[k], 1e-9) << "scene " << scene << " src " << k;
            ASSERT_NEAR(r.coveredArea(), union_area, 1e-9) << "scene " << scene;
            std::shuffle(order.begin(), order.end(), rng);
        }
    }
}

// Once a pixel is full, a polygon behind every piece is dropped without clipping (hiddenInFullPixel). What
// it must not drop: one that shows through a pinhole of 1e-7 px^2 (above the 1e-10 slack), or one that
// comes in front of a piece anywhere, here across a slanted line or at one corner only. Each area is held
// against the inclusion-exclusion oracle, in every insertion order.
TEST(PixelResolver, FullPixelHidesWhatIsBehindItButNotThroughAHoleOrACrossing) {
    const glm::dvec2 pixel(7, 3);
    const double gap = 1e-7;
    struct Case {
        const char* name;
        bool hole;
        Plane last;
    };
    for (const Case& c : {Case{"behind", false, {0.0, 0.0, 0.5}}, Case{"pinhole", true, {0.0, 0.0, 0.5}},
                          Case{"crossing", false, {0.1, 0.1, -0.105}}, Case{"corner", false, {-0.06, 0.05, 1.23}}}) {
        // The front surface (1/z = 1 - 0.01 x) in two halves, split at x = 7.5 with a sliver of a gap when
        // `hole`: the gap is 1e-7 px wide and 1 px tall inside the pixel.
        const Plane front{-0.01, 0.0, 1.0 + 0.01 * 7};
        std::vector<ScreenTriangle> tris = testing::makeQuad(6.5, 2.5, 7.5, 4.5, front, 0);
        for (const auto& t : testing::makeQuad(7.5 + (c.hole ? gap : 0.0), 2.5, 8.5, 4.5, front, 2)) tris.push_back(t);
        tris.push_back(testing::makeTriangle({5, 1}, {11, 1}, {7, 7}, c.last, 4));
        // The last surface against the front's 1.07 - 0.01x (positive 1/z at all its vertices): behind
        // everywhere, or in front past a line through the pixel's centre (crossing), or near the corner
        // (7, 4) alone (corner: 0.05 ((y - 3.8) - (x - 7)) above the front, a 0.02 px^2 triangle).
        std::vector<double> expected(tris.size());
        for (std::size_t k = 0; k < tris.size(); ++k) expected[k] = visibleAreaOracle(tris, k, pixel);
        const std::string name = c.name;
        if (c.hole) {
            EXPECT_NEAR(expected[4], gap, 1e-12);
        } else if (name == "behind") {
            EXPECT_EQ(expected[4], 0.0);
        } else if (name == "corner") {
            EXPECT_NEAR(expected[4], 0.02, 1e-12);
        } else {
            EXPECT_GT(expected[4], 0.1);
        }

        std::vector<std::size_t> order(tris.size());
        std::iota(order.begin(), order.end(), 0);
        PixelResolver r;
        do {
            std::vector<ScreenTriangle> ordered;
            for (std::size_t k : order) ordered.push_back(tris[k]);
            const auto frags = resolvePixel(int(pixel.x), int(pixel.y), ordered, r);
            checkInvariants(int(pixel.x), int(pixel.y), frags);
            auto by = testing::areaBySource(frags);
            // Areas of O(1) pixel-local coordinates (~1e-15 each); the oracle's crossings set the 1e-12.
            for (std::size_t k = 0; k < tris.size(); ++k) ASSERT_NEAR(by[std::uint32_t(k)], expected[k], 1e-12) << c.name << " " << k;
        } while (std::next_permutation(order.begin(), order.end()));
    }
}

}  // namespace clipblur
