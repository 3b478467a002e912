// Edge cases of the exact sweep's closed forms (translatingCells, translatingRectangleCells,
// forEachChordCell) against the test oracle in tests/support, which shares no code with the renderer.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/geometry/chord_sweep.h"
#include "renderer/geometry/translating_coverage.h"
#include "support/translating_coverage.h"

namespace clipblur {

namespace {

using Weights = std::map<std::pair<int, int>, double>;

SmallPolygon small(std::initializer_list<glm::dvec2> pts) {
    SmallPolygon p;
    for (const glm::dvec2& v : pts) p.v[p.n++] = v;
    return p;
}

std::vector<glm::dvec2> vertices(const SmallPolygon& p) { return {p.v.begin(), p.v.begin() + p.n}; }

Weights cells(const SmallPolygon& p, glm::dvec2 d, ChordWeight w = {}) {
    Weights out;
    const auto add = [&](int x, int y, double weight) { out[{x, y}] += weight; };
    translatingCells(p, d, w, add);
    return out;
}

Weights rectangleCells(const MovingRectangle& r, ChordWeight w = {}) {
    Weights out;
    const auto add = [&](int x, int y, double weight) { out[{x, y}] += weight; };
    translatingRectangleCells(r, w, add);
    return out;
}

double total(const Weights& w) {
    double sum = 0.0;
    for (const auto& [pixel, weight] : w) sum += weight;
    return sum;
}

// Every pixel of the swept bounding box against the oracle (so missing pixels count too).
void expectOracle(const Weights& got, const std::vector<glm::dvec2>& p, glm::dvec2 d, double tolerance) {
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const glm::dvec2& v : p) {
        lo = glm::min(lo, glm::min(v, v + d));
        hi = glm::max(hi, glm::max(v, v + d));
    }
    for (int y = static_cast<int>(std::floor(lo.y)) - 1; y <= static_cast<int>(std::ceil(hi.y)); ++y)
        for (int x = static_cast<int>(std::floor(lo.x)) - 1; x <= static_cast<int>(std::ceil(hi.x)); ++x) {
            const auto it = got.find({x, y});
            const double value = it == got.end() ? 0.0 : it->second;
            const double expected = testing::translatingPixelCoverage(p, d, x, y);
            EXPECT_NEAR(value, expected, tolerance) << "pixel " << x << "," << y;
        }
}

std::vector<glm::dvec2> box(glm::dvec2 lo, glm::dvec2 hi) { return {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}}; }

}  // namespace

// Pixels at negative coordinates: cells by floor, not truncation toward zero.
TEST(ExactSweepEdge, PolygonAtNegativeCoordinates) {
    const SmallPolygon p = small({{-3.3, -2.7}, {-1.1, -4.2}, {-0.4, -1.9}});
    const glm::dvec2 d(2.5, 1.75);
    const Weights w = cells(p, d);
    expectOracle(w, vertices(p), d, 1e-12);
    EXPECT_NEAR(total(w), testing::polygonArea(vertices(p)), 1e-12);
}

// Velocity along an edge turned by 1e-14 rad: n.d tiny but not zero, so u_lo/u_hi have slopes ~1e14.
TEST(ExactSweepEdge, VelocityAlmostParallelToAnEdge) {
    for (const double angle : {1e-8, 1e-11, 1e-14, -1e-14, 1e-16}) {
        const SmallPolygon p = small({{10.2, 5.1}, {13.7, 6.3}, {12.9, 8.8}, {9.6, 7.4}});
        const glm::dvec2 e = p.v[1] - p.v[0];
        const glm::dvec2 d = 1.7 * glm::dvec2(e.x * std::cos(angle) - e.y * std::sin(angle), e.x * std::sin(angle) + e.y * std::cos(angle));
        const Weights w = cells(p, d);
        expectOracle(w, vertices(p), d, 1e-10);
        EXPECT_NEAR(total(w), testing::polygonArea(vertices(p)), 1e-10) << angle;
    }
}

// Hundreds of pixels of travel, also at negative coordinates.
TEST(ExactSweepEdge, HugeVelocity) {
    const SmallPolygon p = small({{-20.3, 4.2}, {-18.1, 3.6}, {-17.4, 6.9}, {-19.8, 7.7}});
    const glm::dvec2 d(250.5, -130.25);
    const Weights w = cells(p, d);
    EXPECT_NEAR(total(w), testing::polygonArea(vertices(p)), 1e-9);
    for (const auto& [pixel, weight] : w)
        EXPECT_NEAR(weight, testing::translatingPixelCoverage(vertices(p), d, pixel.first, pixel.second), 1e-11)
            << pixel.first << "," << pixel.second;
}

// Collinear vertices (edge midpoints) and a repeated vertex give the plain square's weights; a polygon of
// zero area gives none.
TEST(ExactSweepEdge, CollinearRepeatedAndZeroArea) {
    const SmallPolygon square = small({{1.25, 1.5}, {3.75, 1.5}, {3.75, 4.0}, {1.25, 4.0}});
    const SmallPolygon padded =
        small({{1.25, 1.5}, {2.5, 1.5}, {3.75, 1.5}, {3.75, 1.5}, {3.75, 2.75}, {3.75, 4.0}, {1.25, 4.0}, {1.25, 4.0}, {1.25, 2.0}});
    for (const glm::dvec2 d : {glm::dvec2(1.5, 0.0), glm::dvec2(0.0, -2.25), glm::dvec2(0.7, 0.3), glm::dvec2(0.0)}) {
        const Weights a = cells(square, d), b = cells(padded, d);
        expectOracle(b, vertices(square), d, 1e-12);
        EXPECT_NEAR(total(b), 6.25, 1e-12);
        for (const auto& [pixel, weight] : a) EXPECT_NEAR(b.count(pixel) ? b.at(pixel) : 0.0, weight, 1e-12);
    }
    const SmallPolygon line = small({{0.5, 0.5}, {1.5, 1.5}, {2.5, 2.5}});
    EXPECT_TRUE(cells(line, glm::dvec2(1.0, 0.0)).empty());
    // Nearly zero area: a sliver triangle.
    const SmallPolygon sliver = small({{0.5, 0.5}, {7.5, 3.5}, {4.0, 2.0 + 1e-13}});
    const glm::dvec2 d(0.3, 1.9);
    expectOracle(cells(sliver, d), vertices(sliver), d, 1e-12);
}

// Polygons whose edges and motion lie exactly on pixel boundaries.
TEST(ExactSweepEdge, PixelAlignedPolygon) {
    const SmallPolygon unit = small({{-2.0, -3.0}, {-1.0, -3.0}, {-1.0, -2.0}, {-2.0, -2.0}});
    for (const glm::dvec2 d : {glm::dvec2(1.0, 0.0), glm::dvec2(2.0, 0.0), glm::dvec2(1.0, 1.0), glm::dvec2(-3.0, 2.0)}) {
        const Weights w = cells(unit, d);
        expectOracle(w, vertices(unit), d, 1e-12);
        EXPECT_NEAR(total(w), 1.0, 1e-12);
    }
    const SmallPolygon triangle = small({{0.0, 0.0}, {2.0, 0.0}, {0.0, 2.0}});
    const glm::dvec2 d(-2.0, 2.0);  // along the hypotenuse
    expectOracle(cells(triangle, d), vertices(triangle), d, 1e-12);
}

// A linear weight w0 + w1 u against the oracle applied to many short pieces of the chord (midpoint rule
// in the weight, exact coverage per piece).
TEST(ExactSweepEdge, LinearWeightAtNegativeCoordinates) {
    const SmallPolygon p = small({{-3.3, -2.7}, {-1.1, -4.2}, {-0.4, -1.9}, {-2.2, -0.8}});
    const glm::dvec2 d(3.5, -1.25);
    const ChordWeight cw{0.7, 0.9};
    const Weights w = cells(p, d, cw);
    EXPECT_NEAR(total(w), testing::polygonArea(vertices(p)) * (cw.w0 + 0.5 * cw.w1), 1e-12);
    const int pieces = 400;
    for (const auto& [pixel, weight] : w) {
        double expected = 0.0;
        for (int k = 0; k < pieces; ++k) {
            const double u0 = double(k) / pieces, um = (k + 0.5) / pieces;
            std::vector<glm::dvec2> start = vertices(p);
            for (glm::dvec2& v : start) v += u0 * d;
            expected += testing::translatingPixelCoverage(start, d / double(pieces), pixel.first, pixel.second) / pieces *
                        (cw.w0 + cw.w1 * um);
        }
        EXPECT_NEAR(weight, expected, 1e-6) << pixel.first << "," << pixel.second;
    }
}

// The rectangle closed form: translating (against the oracle) at negative coordinates and far.
TEST(ExactSweepEdge, RectangleTranslatingAtNegativeCoordinatesAndFar) {
    for (const glm::dvec2 d : {glm::dvec2(2.25, -1.5), glm::dvec2(-180.5, 95.25), glm::dvec2(0.0, 3.0), glm::dvec2(1.0, 1.0)}) {
        const glm::dvec2 lo(-4.3, -2.6), hi(-1.8, -0.9);
        const Weights w = rectangleCells({lo, hi, d, d});
        EXPECT_NEAR(total(w), (hi.x - lo.x) * (hi.y - lo.y), 1e-10);
        for (const auto& [pixel, weight] : w)
            EXPECT_NEAR(weight, testing::translatingPixelCoverage(box(lo, hi), d, pixel.first, pixel.second), 1e-11)
                << pixel.first << "," << pixel.second;
    }
    // Pixel-aligned.
    const Weights w = rectangleCells({{-1.0, -1.0}, {0.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}});
    expectOracle(w, box({-1.0, -1.0}, {0.0, 0.0}), {1.0, 0.0}, 1e-14);
}

// Sides moving at different rates (a stretch) against a fine time quadrature of exact box overlaps.
TEST(ExactSweepEdge, RectangleWithMovingSides) {
    const MovingRectangle r{{-2.3, 1.2}, {-0.6, 2.9}, {1.7, -3.1}, {4.9, 0.4}};
    const ChordWeight cw{1.0, -0.5};
    const Weights w = rectangleCells(r, cw);
    const int steps = 20000;
    Weights expected;
    for (int k = 0; k < steps; ++k) {
        const double u = (k + 0.5) / steps, weight = (cw.w0 + cw.w1 * u) / steps;
        const glm::dvec2 lo = r.lo + u * r.dlo, hi = r.hi + u * r.dhi;
        for (int y = static_cast<int>(std::floor(lo.y)); y < static_cast<int>(std::ceil(hi.y)); ++y)
            for (int x = static_cast<int>(std::floor(lo.x)); x < static_cast<int>(std::ceil(hi.x)); ++x) {
                const double ox = std::min(hi.x, x + 1.0) - std::max(lo.x, double(x));
                const double oy = std::min(hi.y, y + 1.0) - std::max(lo.y, double(y));
                if (ox > 0.0 && oy > 0.0) expected[{x, y}] += ox * oy * weight;
            }
    }
    for (const auto& [pixel, value] : expected)
        EXPECT_NEAR(w.count(pixel) ? w.at(pixel) : 0.0, value, 2e-7) << pixel.first << "," << pixel.second;
    for (const auto& [pixel, value] : w) EXPECT_TRUE(expected.count(pixel)) << pixel.first << "," << pixel.second;
}

// A stretch along x through 0 at s = 1/3 (1 - 3 s): the part after it is cut; what is left weighs
// area * integral over [-1/2, 1/3] of (1 - 3 s) ds = area * 25/24, for a rectangle and for a triangle, at
// any number of positions, at negative coordinates.
TEST(ExactSweepEdge, StretchThroughZeroIsCutExactly) {
    SweepPath path;
    path.pivot = glm::dvec2(-5.5, -3.25);
    path.chord = glm::dvec2(4.0, -2.0);
    path.stretch_chord = glm::dvec2(-3.0, 0.0);
    ConvexPolygon rect, tri;
    for (const glm::dvec2 v : box({-6.25, -4.0}, {-4.5, -2.5})) rect.push(v);
    rect.close();
    for (const glm::dvec2 v : {glm::dvec2(-6.5, -4.0), glm::dvec2(-4.25, -3.5), glm::dvec2(-5.0, -2.0)}) tri.push(v);
    tri.close();
    for (const int m : {1, 2, 3, 7}) {
        for (const ConvexPolygon* q : {&rect, &tri}) {
            double sum = 0.0;
            const auto add = [&](int, int, double w) { sum += w; };
            forEachChordCell(*q, path, m, add);
            const std::vector<glm::dvec2> v(q->v.begin(), q->v.begin() + q->n);
            EXPECT_NEAR(sum, testing::polygonArea(v) * 25.0 / 24.0, 1e-9) << m << " " << q->n;
        }
    }
}

// A translating path at any positions: one exact chord, equal to the oracle, also with a shutter tilt.
TEST(ExactSweepEdge, TranslatingPathWithTiltSumsToItsWeight) {
    SweepPath path;
    path.pivot = glm::dvec2(-0.5, -0.5);
    path.chord = glm::dvec2(-150.25, 60.5);
    path.tilt = 0.8;
    ConvexPolygon q;
    for (const glm::dvec2 v : {glm::dvec2(-1.0, -1.0), glm::dvec2(0.0, -1.0), glm::dvec2(0.3, 0.2)}) q.push(v);
    q.close();
    for (const int m : {1, 4, 9}) {
        Weights w;
        const auto add = [&](int x, int y, double weight) { w[{x, y}] += weight; };
        forEachChordCell(q, path, m, add);
        // integral over [-1/2, 1/2] of 1 + tilt s is 1.
        EXPECT_NEAR(total(w), 0.5 * 1.0 * 1.2 - 0.0, 1e-9) << m;
    }
}

// chordBounds promises the pixels forEachChordCell can reach. A non-rectangle whose stretch changes is
// integrated in parts of constant shape (the part's middle stretch), so at a part's start a vertex is up
// to kChordShapeTolerance (1/128 px) beyond where the chord puts it. Here the rightmost vertex is at x = 7.0
// exactly at s = -1/2 and moves left: the chord ends alone bound x by 7, the parts reach past it, and the
// bounds must hold them.
TEST(ExactSweepEdge, CellsStayInsideChordBounds) {
    SweepPath path;
    path.pivot = glm::dvec2(0.0, 0.0);
    path.chord = glm::dvec2(-10.0, 0.0);         // offset 5 at s = -1/2, -5 at 1/2
    path.stretch_chord = glm::dvec2(1.0, 0.0);   // stretch 0.5 at s = -1/2, 1.5 at 1/2
    ConvexPolygon q;
    for (const glm::dvec2 v : {glm::dvec2(0.0, 0.25), glm::dvec2(4.0, 0.5), glm::dvec2(0.0, 0.75)}) q.push(v);
    q.close();
    const RasterBounds b = chordBounds(q, path, 1);
    EXPECT_GT(b.hi.x, 7.0);
    const int x_end = static_cast<int>(std::ceil(b.hi.x));
    double outside = 0.0;
    const auto add = [&](int x, int, double w) {
        if (x >= x_end) outside += w;
    };
    forEachChordCell(q, path, 1, add);
    EXPECT_EQ(outside, 0.0) << "weight in pixel columns >= " << x_end;
}

// A velocity far below the rounding of the coordinates (|d| << eps |x|) but not zero: the pieces between
// the front edge's lines at u = 0 and u = 1 would be thinner than the rounding of their cut points, with
// covered times scaled by 1 / k; the weights must still sum to the area (the motion is nil).
TEST(ExactSweepEdge, TinyVelocityStaysExact) {
    const SmallPolygon near = small({{10.2, 5.1}, {13.7, 6.3}, {12.9, 8.8}, {9.6, 7.4}});
    SmallPolygon far = near;
    for (int i = 0; i < far.n; ++i) far.v[i] += glm::dvec2(500.0, 300.0);
    const double area = testing::polygonArea(vertices(near));
    for (const double m : {1e-20, 1e-25, 1e-30, 1e-100}) {
        for (const SmallPolygon* p : {&near, static_cast<const SmallPolygon*>(&far)}) {
            const glm::dvec2 d(m, 0.37 * m);
            EXPECT_NEAR(total(cells(*p, d)), area, 1e-9) << "|d| ~ " << m << (p == &far ? " at (500, 300)" : " at (10, 5)");
            EXPECT_NEAR(total(cells(*p, d, {1.0, 0.3})), 1.15 * area, 1e-9) << "|d| ~ " << m << " with w1";
        }
    }
}

// A turning camera (turns: one homography per position, here a pure raster translation by s T) over a
// point that does not move before the turn (chord 0): the polygon translates by T over the interval.
// Through all three knots the chords see that; so must the nested rule's single knot (m = 3: only the
// middle one), continued at the rates the turned outer positions give, or the coarse sweep would stand
// still and accumulateChords' estimated_error (nested minus fine) report the whole blur as error.
TEST(ExactSweepEdge, NestedSingleKnotFollowsTheTurn) {
    const glm::dvec2 T(3.5, -1.25);
    std::vector<glm::dmat3> turns;
    for (int k = 0; k < 3; ++k) {
        const double s = (k + 0.5) / 3.0 - 0.5;
        glm::dmat3 m(1.0);
        m[2][0] = s * T.x;
        m[2][1] = s * T.y;
        turns.push_back(m);
    }
    SweepPath path;
    path.pivot = glm::dvec2(4.5, 4.5);
    path.turns = turns;
    ConvexPolygon q;
    for (const glm::dvec2 v : {glm::dvec2(4.0, 4.0), glm::dvec2(5.25, 4.1), glm::dvec2(4.6, 5.3)}) q.push(v);
    q.close();
    std::vector<glm::dvec2> start(q.v.begin(), q.v.begin() + q.n);
    for (glm::dvec2& v : start) v -= 0.5 * T;
    for (const SweepKnots knots : {SweepKnots::All, SweepKnots::Nested}) {
        Weights w;
        const auto add = [&](int x, int y, double weight) { w[{x, y}] += weight; };
        forEachChordCell(q, path, 3, add, knots);
        double worst = 0.0;
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 10; ++x) {
                const double got = w.count({x, y}) ? w.at({x, y}) : 0.0;
                worst = std::max(worst, std::abs(got - testing::translatingPixelCoverage(start, T, x, y)));
            }
        EXPECT_LT(worst, 1e-12) << (knots == SweepKnots::All ? "All" : "Nested");
    }
}

}  // namespace clipblur
