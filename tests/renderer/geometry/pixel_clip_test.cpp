#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "renderer/geometry/pixel_clip.h"
#include "renderer/geometry/predicates.h"

namespace clipblur {

namespace {

struct PixelPieces {
    std::map<std::pair<int, int>, ConvexPolygon> pieces;
    CompensatedSum area;
};

PixelPieces clipToGrid(const TriangleClipper& clip) {
    PixelPieces out;
    const auto& t = clip.vertices();
    const int x0 = int(std::floor(std::min({t[0].x, t[1].x, t[2].x})));
    const int x1 = int(std::floor(std::max({t[0].x, t[1].x, t[2].x})));
    const int y0 = int(std::floor(std::min({t[0].y, t[1].y, t[2].y})));
    const int y1 = int(std::floor(std::max({t[0].y, t[1].y, t[2].y})));
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            ConvexPolygon p;
            clip.clipToPixel(x, y, p);
            if (p.degenerate()) continue;
            out.area.add(p.area());
            out.pieces[{x, y}] = p;
        }
    }
    return out;
}

}  // namespace

TEST(PixelClip, RightTriangleOnPixelBoundariesHasHalfPixelsOnTheDiagonal) {
    const TriangleClipper clip({glm::dvec2(10, 20), glm::dvec2(14, 20), glm::dvec2(10, 24)});
    const PixelPieces pp = clipToGrid(clip);
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            const double expected = i + j < 3 ? 1.0 : (i + j == 3 ? 0.5 : 0.0);
            const auto it = pp.pieces.find({10 + i, 20 + j});
            const double got = it == pp.pieces.end() ? 0.0 : it->second.area();
            EXPECT_EQ(got, expected) << i << "," << j;
        }
    }
    EXPECT_EQ(pp.area.value(), 8.0);
}

TEST(PixelClip, PixelAreasSumToTriangleAreaOnRandomTriangles) {
    std::mt19937_64 rng(1234);
    std::uniform_real_distribution<double> centre(-500.0, 1500.0);
    std::uniform_real_distribution<double> size(0.01, 12.0);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 500; ++i) {
        const glm::dvec2 c(centre(rng), centre(rng));
        const double s = size(rng);
        const TriangleClipper clip({c + s * glm::dvec2(u(rng), u(rng)), c + s * glm::dvec2(u(rng), u(rng)),
                                    c + s * glm::dvec2(u(rng), u(rng))});
        if (!clip.valid()) continue;
        const PixelPieces pp = clipToGrid(clip);
        // Each piece's area carries a few ulps of its O(1500) coordinates; 1e-12 relative (plus an
        // absolute 1e-12 px^2 for tiny triangles) is far above that and far below any lost pixel piece.
        ASSERT_NEAR(pp.area.value(), clip.area(), 1e-12 * clip.area() + 1e-12) << i;
    }
}

TEST(PixelClip, NeighbouringPixelsShareBitIdenticalVertices) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(0.0, 9.0);
    for (int i = 0; i < 200; ++i) {
        const glm::dvec2 off(1234.0, 567.0);
        const TriangleClipper clip({off + glm::dvec2(u(rng), u(rng)), off + glm::dvec2(u(rng), u(rng)),
                                    off + glm::dvec2(u(rng), u(rng))});
        if (!clip.valid()) continue;
        const PixelPieces pp = clipToGrid(clip);
        for (const auto& [pix, poly] : pp.pieces) {
            for (int k = 0; k < poly.n; ++k) {
                const glm::dvec2 v = poly.v[k];
                // A vertex on the right (bottom) edge must be a vertex of the right (lower) neighbour.
                for (int axis = 0; axis < 2; ++axis) {
                    const int edge = (axis == 0 ? pix.first : pix.second) + 1;
                    if (v[axis] != edge) continue;
                    const auto nb = pp.pieces.find(axis == 0 ? std::make_pair(pix.first + 1, pix.second)
                                                             : std::make_pair(pix.first, pix.second + 1));
                    if (nb == pp.pieces.end()) continue;  // touches the neighbour in a point only
                    bool found = false;
                    for (int m = 0; m < nb->second.n; ++m) found |= nb->second.v[m] == v;
                    ASSERT_TRUE(found) << "triangle " << i << " pixel " << pix.first << "," << pix.second;
                }
            }
        }
    }
}

TEST(PixelClip, StripThenColumnEqualsDirectPixelClip) {
    const TriangleClipper clip({glm::dvec2(0.3, 0.1), glm::dvec2(7.9, 2.2), glm::dvec2(2.6, 6.7)});
    for (int y = 0; y < 7; ++y) {
        TriangleClipper::Piece strip;
        clip.clipToStrip(y, y + 1.0, strip);
        for (int x = 0; x < 8; ++x) {
            ConvexPolygon a, b;
            clip.clipToColumn(strip, x, x + 1.0, a);
            clip.clipToPixel(x, y, b);
            ASSERT_EQ(a.n, b.n);
            for (int k = 0; k < a.n; ++k) EXPECT_EQ(a.v[k], b.v[k]);
        }
    }
}

TEST(PixelClip, SliverTriangleKeepsOrientationAndArea) {
    // 1e-9 px wide, 6 px long, crossing pixel columns: area 3e-9 px^2 must survive the clip.
    const glm::dvec2 a(100.25, 200.5), b(106.25, 200.5), c(103.0, 200.5 + 1e-9);
    const TriangleClipper clip({a, b, c});
    ASSERT_TRUE(clip.valid());
    EXPECT_GT(orient2d(a, b, c), 0.0);
    EXPECT_LT(orient2d(a, c, b), 0.0);
    const PixelPieces pp = clipToGrid(clip);
    const double exact = 0.5 * 6.0 * ((200.5 + 1e-9) - 200.5);  // the height as stored in double
    EXPECT_NEAR(clip.area(), exact, 1e-12 * exact);
    // Relative accuracy is not attainable here: each crossing ordinate near y = 200 is rounded to
    // ulp(200) = 2^-45 px, against a height of 1e-9 px. The bound is absolute: per piece (7 columns) two
    // crossing vertices, each off by at most half an ulp over a 1 px wide piece.
    EXPECT_NEAR(pp.area.value(), exact, 7 * 2 * 0.5 * std::ldexp(1.0, -45));
    for (const auto& [pix, poly] : pp.pieces) EXPECT_GE(poly.area(), 0.0);
}

TEST(PixelClip, DegenerateAndNonFiniteTrianglesAreInvalid) {
    EXPECT_FALSE(TriangleClipper({glm::dvec2(0, 0), glm::dvec2(1, 1), glm::dvec2(2, 2)}).valid());
    EXPECT_FALSE(TriangleClipper({glm::dvec2(0, 0), glm::dvec2(NAN, 1), glm::dvec2(2, 0)}).valid());
    EXPECT_FALSE(TriangleClipper({glm::dvec2(0, 0), glm::dvec2(INFINITY, 1), glm::dvec2(2, 0)}).valid());
}

}  // namespace clipblur
