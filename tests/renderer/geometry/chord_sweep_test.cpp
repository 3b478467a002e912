#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/geometry/chord_sweep.h"
#include "support/translating_coverage.h"

namespace clipblur {

namespace {

using Weights = std::map<std::pair<int, int>, double>;

Weights collect(const ConvexPolygon& q, SweepPath path, int positions, SweepKnots knots = SweepKnots::All) {
    Weights w;
    const auto add = [&](int x, int y, double weight) { w[{x, y}] += weight; };
    forEachChordCell(q, path, positions, add, knots);
    return w;
}

// A random convex polygon inside the unit pixel with corner `at` (a fragment): the hull (monotone chain)
// of 3 to 8 random points in it.
ConvexPolygon randomFragment(std::mt19937& rng, glm::dvec2 at) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 3 + static_cast<int>(rng() % 6);
    std::vector<glm::dvec2> pts;
    for (int i = 0; i < n; ++i) pts.push_back(at + glm::dvec2(u(rng), u(rng)));
    std::sort(pts.begin(), pts.end(), [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    const auto cross = [](const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<glm::dvec2> hull;
    for (int pass = 0; pass < 2; ++pass) {
        const std::size_t base = hull.size();
        for (const glm::dvec2& p : pts) {
            while (hull.size() >= base + 2 && cross(hull[hull.size() - 2], hull.back(), p) <= 0.0) hull.pop_back();
            hull.push_back(p);
        }
        hull.pop_back();
        std::reverse(pts.begin(), pts.end());
    }
    ConvexPolygon p;
    for (const glm::dvec2& q : hull) p.push(q);  // counter-clockwise
    p.close();
    if (p.degenerate()) return randomFragment(rng, at);
    return p;
}

std::vector<glm::dvec2> vertices(const ConvexPolygon& p) { return {p.v.begin(), p.v.begin() + p.n}; }

// A path's offset and stretch at s without a turn.
glm::dvec2 offsetAt(const SweepPath& path, double s) {
    glm::dvec2 offset, stretch;
    path.place(s, nullptr, offset, stretch);
    return offset;
}
glm::dvec2 stretchAt(const SweepPath& path, double s) {
    glm::dvec2 offset, stretch;
    path.place(s, nullptr, offset, stretch);
    return stretch;
}


// The chords the sweep integrates, restated here from forEachChordCell's contract: knots at the midpoints
// s_k = (k + 1/2) / m - 1/2 placed on the path, linear between them, continued at the first and last
// chord's velocity to s = -1/2 and 1/2 (for one knot, at the path's velocity there, `chord` when s = 0).
// For paths without stretch (the oracle translates a fixed shape). Expected per pixel: the sum over chords
// of their span times the oracle's exact time-averaged coverage of the polygon translating along them.
Weights chordOracle(const ConvexPolygon& q, const SweepPath& path, int m) {
    struct Knot {
        double s;
        glm::dvec2 offset, stretch;
    };
    std::vector<Knot> knots;
    for (int k = 0; k < m; ++k) {
        const double s = (k + 0.5) / m - 0.5;
        knots.push_back({s, offsetAt(path, s), stretchAt(path, s)});
    }
    struct Chord {
        double s0, s1;
        glm::dvec2 from, to, stretch;
    };
    std::vector<Chord> chords;
    const glm::dvec2 v0 = m == 1 ? path.chord : (knots[1].offset - knots[0].offset) * double(m);
    const glm::dvec2 v1 = m == 1 ? path.chord : (knots[m - 1].offset - knots[m - 2].offset) * double(m);
    chords.push_back({-0.5, knots[0].s, knots[0].offset - (knots[0].s + 0.5) * v0, knots[0].offset, knots[0].stretch});
    for (int k = 0; k + 1 < m; ++k)
        chords.push_back({knots[k].s, knots[k + 1].s, knots[k].offset, knots[k + 1].offset,
                          0.5 * (knots[k].stretch + knots[k + 1].stretch)});
    chords.push_back({knots[m - 1].s, 0.5, knots[m - 1].offset, knots[m - 1].offset + (0.5 - knots[m - 1].s) * v1,
                      knots[m - 1].stretch});
    Weights w;
    for (const Chord& c : chords) {
        if (!(c.stretch.x > 0.0 && c.stretch.y > 0.0)) continue;
        std::vector<glm::dvec2> start;
        for (int i = 0; i < q.n; ++i) start.push_back(path.pivot + c.from + c.stretch * (q.v[i] - path.pivot));
        glm::dvec2 lo(1e300), hi(-1e300);
        for (const glm::dvec2& p : start) {
            lo = glm::min(glm::min(lo, p), p + c.to - c.from);
            hi = glm::max(glm::max(hi, p), p + c.to - c.from);
        }
        for (int y = int(std::floor(lo.y)); y < int(std::ceil(hi.y)); ++y)
            for (int x = int(std::floor(lo.x)); x < int(std::ceil(hi.x)); ++x) {
                const double cover = testing::translatingPixelCoverage(start, c.to - c.from, x, y);
                if (cover > 0.0) w[{x, y}] += (c.s1 - c.s0) * cover;
            }
    }
    return w;
}

// Every pixel of `got` and `expected` within tol of the other (a pixel missing from one counts as 0).
void expectWeights(const Weights& got, const Weights& expected, double tol, const std::string& what) {
    for (const auto& [pixel, weight] : got) {
        const auto it = expected.find(pixel);
        EXPECT_NEAR(weight, it == expected.end() ? 0.0 : it->second, tol) << what << " pixel " << pixel.first << "," << pixel.second;
    }
    for (const auto& [pixel, weight] : expected)
        if (!got.count(pixel)) {
            EXPECT_NEAR(weight, 0.0, tol) << what << " missing pixel " << pixel.first << "," << pixel.second;
        }
}

}  // namespace
// A unit square moving two pixels right is, over the interval, a tent: 1/2 stays in its pixel and 1/4
// reaches each neighbour (the integral of max(0, 1 - |2s|) and of max(0, 2s) over s in [-1/2, 1/2]). Time
// is integrated exactly, so that holds for any number of positions (midpoint samples gave 1/2 + 1/(2 m^2)
// for odd m, a node on the kink).
TEST(ChordSweep, UnitSquareMovingTwoPixelsIsATent) {
    const ConvexPolygon square = [] {
        ConvexPolygon p;
        for (glm::dvec2 v : {glm::dvec2(3, 5), glm::dvec2(4, 5), glm::dvec2(4, 6), glm::dvec2(3, 6)}) p.push(v);
        p.close();
        return p;
    }();
    ConvexPolygon diamond;  // the same test through the general (non-rectangle) path: a square turned 45 deg
    for (glm::dvec2 v : {glm::dvec2(3.5, 5), glm::dvec2(4, 5.5), glm::dvec2(3.5, 6), glm::dvec2(3, 5.5)}) diamond.push(v);
    diamond.close();
    for (int m : {1, 2, 3, 8, 9}) {
        const Weights w = collect(square, {{2.0, 0.0}, {0.0, 0.0}}, m);
        EXPECT_NEAR(w.at({3, 5}), 0.5, 1e-12) << m;
        EXPECT_NEAR(w.at({2, 5}), 0.25, 1e-12) << m;
        EXPECT_NEAR(w.at({4, 5}), 0.25, 1e-12) << m;
        EXPECT_EQ(w.size(), 3u) << m;
        // The diamond (area 1/2) moving 2 px: the same by the oracle.
        std::vector<glm::dvec2> start = vertices(diamond);
        for (glm::dvec2& p : start) p -= glm::dvec2(1.0, 0.0);
        for (const auto& [pixel, weight] : collect(diamond, {{2.0, 0.0}, {0.0, 0.0}}, m))
            EXPECT_NEAR(weight, testing::translatingPixelCoverage(start, {2.0, 0.0}, pixel.first, pixel.second), 1e-12) << m;
    }
}

// Seeded random fragments and paths against the test oracle (tests/support: its own box clip and
// breakpoint-exact Gauss-Legendre time integral, no renderer code). (1) On a straight path the sweep is the
// exact time-integrated coverage whatever the positions (1e-11: rounding of cuts on coordinates ~20).
// (2) On a bent path it is the exact integral along the chords through the positions (chordOracle), and
// the weights sum to the fragment's area. (3) It converges to the bent path's exact coverage as the
// chords' deviation from the parabola does, O(1/m^2).
TEST(ChordSweep, IsTheExactTimeIntegralAlongItsChords) {
    std::mt19937 rng(20261122);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (int trial = 0; trial < 200; ++trial) {
        ConvexPolygon q = randomFragment(rng, glm::dvec2(10, 20));
        if (trial % 4 == 0) {  // an axis-aligned part-pixel: the separable path
            const RasterBounds b = q.bounds();
            q.clear();
            for (const glm::dvec2& v : {b.lo, glm::dvec2(b.hi.x, b.lo.y), b.hi, glm::dvec2(b.lo.x, b.hi.y)}) q.push(v);
        }
        const glm::dvec2 d(u(rng), u(rng));
        const glm::dvec2 bend = 0.2 * glm::dvec2(u(rng), u(rng));
        const std::vector<glm::dvec2> poly = vertices(q);
        const double area = testing::polygonArea(poly);
        std::vector<glm::dvec2> start = poly;  // the oracle moves p to p + v; the sweep is centred
        for (glm::dvec2& p : start) p -= 0.5 * d;
        for (int m : {1, 2, 3, 5}) {
            Weights exact;
            for (const auto& [pixel, weight] : collect(q, {d, glm::dvec2(0.0)}, m))
                exact[pixel] = testing::translatingPixelCoverage(start, d, pixel.first, pixel.second);
            expectWeights(collect(q, {d, glm::dvec2(0.0)}, m), exact, 1e-11, "straight m " + std::to_string(m));
            const Weights w = collect(q, {d, bend}, m);
            double total = 0.0;
            for (const auto& [pixel, weight] : w) total += weight;
            EXPECT_NEAR(total, area, 1e-11) << trial;
            expectWeights(w, chordOracle(q, {d, bend}, m), 1e-11, "bent m " + std::to_string(m));
        }
    }
}

// On a bent path the chords' error falls as 1/m^2: the largest pixel error against a dense chord rule
// (m = 512, itself within ~1e-6 of the parabola) drops about 4x per doubling of m.
TEST(ChordSweep, BentPathConvergesQuadratically) {
    std::mt19937 rng(20261127);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    double ratio_sum = 0.0;
    int ratios = 0;
    for (int trial = 0; trial < 20; ++trial) {
        const ConvexPolygon q = randomFragment(rng, glm::dvec2(10, 20));
        const SweepPath path{glm::dvec2(u(rng), u(rng)), glm::dvec2(u(rng), u(rng))};
        const Weights reference = collect(q, path, 512);
        double previous = 0.0;
        for (int m : {8, 16, 32}) {
            double worst = 0.0;
            Weights w = collect(q, path, m);
            for (const auto& [pixel, weight] : reference) worst = std::max(worst, std::abs(w[pixel] - weight));
            if (previous > 0.0 && worst > 1e-9) {
                ratio_sum += previous / worst;
                ++ratios;
            }
            previous = worst;
        }
    }
    ASSERT_GT(ratios, 20);
    // A first-order rule would give 2; the mean of chord errors per doubling is near 4.
    EXPECT_GT(ratio_sum / ratios, 3.0);
}

// chordBounds is the box of every chord's polygon at both its ends (chordOracle's construction: the
// positions and the interval's ends continued along the first and last chord, offset and stretch alike),
// which holds the polygon throughout, its vertices moving linearly along each chord, grown by the shape
// tolerance of the parts a reshaping polygon is cut into. Seeded random paths with bend, stretch and depth
// terms.
TEST(ChordSweep, BoundsAreTheChordEnds) {
    std::mt19937 rng(20261124);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int checked = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const ConvexPolygon q = randomFragment(rng, glm::dvec2(10, 20));
        SweepPath path;
        path.pivot = glm::dvec2(10.5, 20.5) + 0.3 * glm::dvec2(u(rng), u(rng));
        path.chord = 30.0 * glm::dvec2(u(rng), u(rng));
        path.bend = 5.0 * glm::dvec2(u(rng), u(rng));
        path.stretch_chord = 0.8 * glm::dvec2(u(rng), u(rng));
        path.stretch_bend = 0.3 * glm::dvec2(u(rng), u(rng));
        const double wa = 1.0 + 0.7 * u(rng), wb = 1.0 + 0.7 * u(rng);
        path.depth_chord = wb - wa;
        path.depth_bend = 0.5 * (wa + wb) - 1.0 + 0.2 * u(rng);
        double least = 1.0;
        for (int i = 0; i <= 1000; ++i) least = std::min(least, path.depthAt(i / 1000.0 - 0.5));
        if (least < 0.1) continue;
        ++checked;
        for (int m : {1, 2, 5, 17}) {
            const RasterBounds b = chordBounds(q, path, m);
            glm::dvec2 lo(1e300), hi(-1e300);
            const RasterBounds box = q.bounds();
            std::vector<glm::dvec2> offsets, stretches;
            for (int k = 0; k < m; ++k) {
                offsets.push_back(offsetAt(path, (k + 0.5) / m - 0.5));
                stretches.push_back(stretchAt(path, (k + 0.5) / m - 0.5));
            }
            const glm::dvec2 v0 = m == 1 ? path.chord : (offsets[1] - offsets[0]) * double(m);
            const glm::dvec2 v1 = m == 1 ? path.chord : (offsets[m - 1] - offsets[m - 2]) * double(m);
            glm::dvec2 most(0.0);  // the largest stretch at a chord end, per axis
            const auto hold = [&](const glm::dvec2& offset, const glm::dvec2& stretch) {
                most = glm::max(most, stretch);
                for (const glm::dvec2& corner : {box.lo, box.hi}) {
                    const glm::dvec2 p = path.pivot + offset + stretch * (corner - path.pivot);
                    lo = glm::min(lo, p);
                    hi = glm::max(hi, p);
                }
            };
            // The end chords continue the first and last chord's stretch rate too (at m = 1 the path's at 0:
            // stretch_chord - depth_chord, n' w - n w' with n = w = 1 there).
            const glm::dvec2 r0 = m == 1 ? path.stretch_chord - path.depth_chord : (stretches[1] - stretches[0]) * double(m);
            const glm::dvec2 r1 = m == 1 ? r0 : (stretches[m - 1] - stretches[m - 2]) * double(m);
            hold(offsets[0] - (0.5 / m) * v0, stretches[0] - (0.5 / m) * r0);
            hold(offsets[m - 1] + (0.5 / m) * v1, stretches[m - 1] + (0.5 / m) * r1);
            for (int k = 0; k < m; ++k) hold(offsets[k], stretches[k]);
            // The stretch stays positive here (>= 0.3 / 1.7), so every chord counts; it changes along every
            // chord of these (non-rectangle) fragments, so the box is grown by the parts' shape tolerance
            // at the largest stretch (a share of the stretched half-size where that exceeds 1/128 px).
            const glm::dvec2 half = 0.5 * (box.hi - box.lo);
            const double grow = std::max(chordShapeTolerance(most.x, half.x), chordShapeTolerance(most.y, half.y));
            EXPECT_NEAR(b.lo.x, lo.x - grow, 1e-9) << trial << " m " << m;
            EXPECT_NEAR(b.lo.y, lo.y - grow, 1e-9) << trial << " m " << m;
            EXPECT_NEAR(b.hi.x, hi.x + grow, 1e-9) << trial << " m " << m;
            EXPECT_NEAR(b.hi.y, hi.y + grow, 1e-9) << trial << " m " << m;
        }
    }
    EXPECT_GT(checked, 200);
}

// A surface turning away: the x stretch runs from 1 at s = -1/2 through 1 at 0 to -1 at 1/2, numerator
// 1 - 2 s - 4 s^2 over a depth ratio of 1. Along a chord the stretch goes linearly between its ends (the
// end chords continue the neighbouring chord's rate; with one knot the path's, -2 at s = 0), and a chord
// counts only while it is positive, cut where it crosses 0, so the weights sum to the integral of the
// positive part of that piecewise-linear stretch (the square's stretched area).
TEST(ChordSweep, TimeWhereTheSurfaceFacesAwayIsLeftOut) {
    ConvexPolygon square;
    for (glm::dvec2 v : {glm::dvec2(3, 5), glm::dvec2(4, 5), glm::dvec2(4, 6), glm::dvec2(3, 6)}) square.push(v);
    square.close();
    SweepPath path;
    path.chord = glm::dvec2(4.0, 0.0);
    path.pivot = glm::dvec2(3.5, 5.5);
    path.setStretch(glm::dvec2(1.0), glm::dvec2(-1.0, 1.0));
    const auto numerator = [](double s) { return 1.0 - 2.0 * s - 4.0 * s * s; };
    for (int m : {1, 4, 7, 16}) {
        struct Span {
            double s0, s1, from, to;  // x stretch at s0 and s1
        };
        std::vector<Span> spans;
        const double first = 0.5 / m - 0.5, last = -first;
        const double rate_first = m == 1 ? -2.0 : (numerator(first + 1.0 / m) - numerator(first)) * m;
        const double rate_last = m == 1 ? -2.0 : (numerator(last) - numerator(last - 1.0 / m)) * m;
        spans.push_back({-0.5, first, numerator(first) - (first + 0.5) * rate_first, numerator(first)});
        for (int k = 0; k + 1 < m; ++k) {
            const double s = (k + 0.5) / m - 0.5;
            spans.push_back({s, s + 1.0 / m, numerator(s), numerator(s + 1.0 / m)});
        }
        spans.push_back({last, 0.5, numerator(last), numerator(last) + (0.5 - last) * rate_last});
        double expected = 0.0;
        for (const Span& c : spans) {
            const double span = c.s1 - c.s0;
            if (c.from > 0.0 && c.to > 0.0) expected += span * 0.5 * (c.from + c.to);
            if (c.from > 0.0 && c.to <= 0.0) expected += span * (c.from / (c.from - c.to)) * 0.5 * c.from;
            if (c.from <= 0.0 && c.to > 0.0) expected += span * (c.to / (c.to - c.from)) * 0.5 * c.to;
        }
        double total = 0.0;
        for (const auto& [pixel, weight] : collect(square, path, m)) total += weight;
        EXPECT_NEAR(total, expected, 1e-12) << m;
        if (m == 1) continue;  // one chord, 2 -> 0 by the rate at s = 0: a mean of 1 by chance
        EXPECT_GT(total, 0.3) << m;
        EXPECT_LT(total, 0.95) << m;  // the share after the turn is gone
    }
}


// A sliver turning to face the camera: a thin slanted quad 8 px wide whose x stretch grows from 0 to 2
// over the interval while it translates. Cut into parts of 1/128 px of vertex error, that is 512 parts
// (half the change, 2 x 4 px, over 1/128); cut by ratio where the stretched half-size passes 1 px, about
// 200. Against a time-sampled reference (2,048 slices, each the exact oracle for a held shape translating,
// the slices' own shape error 1/1,024 px), the weights hold to 1e-4 per pixel (measured 4.7e-6; the tip
// of this 0.05 px tall sliver held 1/128 px off for the whole interval would move 3.9e-4) and sum to its
// area.
TEST(ChordSweep, GrowingSliverIsCutByRatio) {
    ConvexPolygon q;
    for (glm::dvec2 v : {glm::dvec2(10, 20.40), glm::dvec2(18, 20.46), glm::dvec2(18, 20.51), glm::dvec2(10, 20.45)}) q.push(v);
    q.close();
    SweepPath path;
    path.pivot = glm::dvec2(14.0, 20.455);
    path.chord = glm::dvec2(3.0, 0.5);
    path.stretch_chord = glm::dvec2(2.0, 0.0);  // x stretch 0 at s = -1/2, 2 at 1/2
    long adds = 0;
    Weights got;
    const auto add = [&](int x, int y, double w) {
        ++adds;
        got[{x, y}] += w;
    };
    forEachChordCell(q, path, 1, add);
    const int slices = 2048;
    Weights reference;
    const std::vector<glm::dvec2> poly = vertices(q);
    for (int k = 0; k < slices; ++k) {
        const double s0 = -0.5 + double(k) / slices, mid = s0 + 0.5 / slices;
        const glm::dvec2 stretch(1.0 + 2.0 * mid, 1.0), move = path.chord / double(slices);
        std::vector<glm::dvec2> start;
        for (const glm::dvec2& v : poly) start.push_back(path.pivot + s0 * path.chord + stretch * (v - path.pivot));
        glm::dvec2 lo(1e300), hi(-1e300);
        for (const glm::dvec2& p : start) {
            lo = glm::min(glm::min(lo, p), p + move);
            hi = glm::max(glm::max(hi, p), p + move);
        }
        for (int y = int(std::floor(lo.y)); y < int(std::ceil(hi.y)); ++y)
            for (int x = int(std::floor(lo.x)); x < int(std::ceil(hi.x)); ++x)
                reference[{x, y}] += testing::translatingPixelCoverage(start, move, x, y) / slices;
    }
    expectWeights(got, reference, 1e-4, "growing sliver");
    double total = 0.0;
    for (const auto& [pixel, weight] : got) total += weight;
    // The stretch's mean over the interval is 1, so the weights sum to the area (1e-12: rounding).
    EXPECT_NEAR(total, testing::polygonArea(poly), 1e-12);
    // The same sweep in 512 uniform parts, each translatingCells of its middle shape, adds cells more than
    // twice as often.
    long uniform_adds = 0;
    const auto count = [&](int, int, double) { ++uniform_adds; };
    const int uniform = 512;
    for (int k = 0; k < uniform; ++k) {
        const double s0 = -0.5 + double(k) / uniform, mid = s0 + 0.5 / uniform;
        SmallPolygon part;
        part.n = q.n;
        for (int i = 0; i < q.n; ++i)
            part.v[i] = path.pivot + s0 * path.chord + glm::dvec2(1.0 + 2.0 * mid, 1.0) * (q.v[i] - path.pivot);
        translatingCells(part, path.chord / double(uniform), {1.0 / uniform, 0.0}, count);
    }
    EXPECT_LT(2 * adds, uniform_adds) << adds << " against " << uniform_adds;
}

}  // namespace clipblur
