#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "renderer/geometry/swept_footprint.h"
#include "support/translating_coverage.h"

namespace clipblur {

namespace {

using Weights = std::map<std::pair<int, int>, double>;

Weights collect(const ConvexPolygon& q, SweepPath path, int positions) {
    std::vector<PixelWeight> out;
    sweptFootprint(q, path, positions, out);
    Weights w;
    for (const PixelWeight& p : out) w[{p.x, p.y}] += p.weight;
    return w;
}

// A random convex polygon inside the unit pixel with corner `at` (a fragment): the hull of random points.
ConvexPolygon randomFragment(std::mt19937& rng, glm::dvec2 at) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 3 + static_cast<int>(rng() % 6);
    std::vector<glm::dvec2> pts;
    const glm::dvec2 c(u(rng), u(rng));
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * M_PI * (i + 0.8 * u(rng)) / n;
        // A point on the ray from c at angle a, inside the pixel.
        const glm::dvec2 dir(std::cos(a), std::sin(a));
        double t = 1e9;
        for (int k = 0; k < 2; ++k) {
            if (dir[k] > 0) t = std::min(t, (1.0 - c[k]) / dir[k]);
            if (dir[k] < 0) t = std::min(t, -c[k] / dir[k]);
        }
        pts.push_back(at + c + (0.2 + 0.8 * u(rng)) * t * dir);
    }
    ConvexPolygon p;
    for (const glm::dvec2& q : pts) p.push(q);  // angularly sorted about c: convex
    p.close();
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

}  // namespace

// A unit square moving two pixels right is, averaged over the interval, a tent: 1/2 stays in its pixel and
// 1/4 reaches each neighbour (the integral of max(0, 1 - |2s|) and of max(0, 2s) over s in [-1/2, 1/2]).
// At M positions (the midpoint rule) the pixel's own weight is exactly 1/2 for even M, whose nodes
// straddle the kink at s = 0 so the rule is exact on both linear pieces, and 1 - 2 mean|s_k| =
// 1/2 + 1/(2 M^2) for odd M, which puts a node on the kink.
TEST(SweptFootprint, UnitSquareMovingTwoPixelsIsATent) {
    const ConvexPolygon square = [] {
        ConvexPolygon p;
        for (glm::dvec2 v : {glm::dvec2(3, 5), glm::dvec2(4, 5), glm::dvec2(4, 6), glm::dvec2(3, 6)}) p.push(v);
        p.close();
        return p;
    }();
    for (int m : {2, 3, 8, 9}) {
        const Weights w = collect(square, {{2.0, 0.0}, {0.0, 0.0}}, m);
        EXPECT_NEAR(w.at({3, 5}), m % 2 == 0 ? 0.5 : 0.5 + 0.5 / (m * m), 1e-12) << m;
        EXPECT_NEAR(w.at({2, 5}), w.at({4, 5}), 1e-12) << m;
        EXPECT_NEAR(w.at({2, 5}) + w.at({3, 5}) + w.at({4, 5}), 1.0, 1e-12) << m;
    }
}

// Seeded random fragments and paths. (1) The weights sum to the fragment's area, and (2) at each position
// the weights are the pixel areas of the shifted polygon, computed here by the test oracle's own box clip
// (tests/support, no renderer code), at the parabola's offset written out here from its definition.
// (3) On a straight path many positions converge to the exact time-integrated coverage (the oracle's
// breakpoint-exact integral) as the midpoint rule does: error O(1/M^2).
TEST(SweptFootprint, MatchesIndependentClipAndConvergesToTheExactIntegral) {
    std::mt19937 rng(20261122);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (int trial = 0; trial < 200; ++trial) {
        const ConvexPolygon q = randomFragment(rng, glm::dvec2(10, 20));
        const glm::dvec2 d(u(rng), u(rng));
        const glm::dvec2 bend = 0.2 * glm::dvec2(u(rng), u(rng));
        const std::vector<glm::dvec2> poly = vertices(q);
        const double area = testing::polygonArea(poly);
        // Offsets 0 at s = 0 and -d/2 + bend, d/2 + bend at the ends: s d + 4 s^2 bend.
        const auto offset = [&](double s) { return s * d + 4.0 * s * s * bend; };
        for (int m : {1, 3, 4}) {
            const Weights w = collect(q, {d, bend}, m);
            double total = 0.0;
            for (const auto& [pixel, weight] : w) total += weight;
            // Rounding of a few cuts and shoelace sums on coordinates ~20: far below 1e-12 px^2.
            EXPECT_NEAR(total, area, 1e-12) << trial;
            for (const auto& [pixel, weight] : w) {
                double expected = 0.0;
                for (int k = 0; k < m; ++k) {
                    std::vector<glm::dvec2> moved = poly;
                    for (glm::dvec2& p : moved) p += offset((k + 0.5) / m - 0.5);
                    const glm::dvec2 lo(pixel.first, pixel.second);
                    expected += testing::polygonArea(testing::clipToBox(moved, lo, lo + 1.0)) / m;
                }
                EXPECT_NEAR(weight, expected, 1e-12) << trial << " pixel " << pixel.first << "," << pixel.second;
            }
        }
        // translatingCoverage moves the polygon from p to p + v; ours is centred, so start at p - d/2.
        std::vector<glm::dvec2> start = poly;
        for (glm::dvec2& p : start) p -= 0.5 * d;
        const Weights fine = collect(q, {d, glm::dvec2(0.0)}, 400);
        for (const auto& [pixel, weight] : fine) {
            const double exact = testing::translatingPixelCoverage(start, d, pixel.first, pixel.second);
            // Midpoint rule over a piecewise quadratic with kinks: error <= (slope jump) h^2 / 8 per kink,
            // slope jumps <= |d| (an edge of length <= 1.5 px sweeping), a handful of kinks: 1e-4 at h = 1/400.
            EXPECT_NEAR(weight, exact, 1e-4) << trial;
        }
    }
}

// SweepPath::through a point's raster positions and depths at s = -1/2, 0, 1/2 follows the point exactly
// when it moves linearly in camera space (camera and object translation: a pan, a dolly), whatever the
// perspective bends; the raster parabola through the same three positions does not. Projected here by
// hand with a pinhole of focal length f (raster = c + f (x / z, -y / z)). A surface facing the camera
// scales as depth(0) / depth(s): with the stretch set from its ends the stretch is that, exactly.
TEST(SweepPath, ThroughFollowsATranslatingPointExactly) {
    std::mt19937 rng(20261123);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double f = 600.0;
    const glm::dvec2 c(640.0, 360.0);
    double raster_parabola = 0.0;
    for (int trial = 0; trial < 500; ++trial) {
        const glm::dvec3 p0(5.0 * u(rng), 3.0 * u(rng), 6.0 + 4.0 * u(rng));  // depth 2 .. 10
        // |s v.z| <= p0.z - 1 for |s| <= 1/2: depth stays >= 1 over the interval.
        const glm::dvec3 v(4.0 * u(rng), 4.0 * u(rng), 2.0 * (p0.z - 1.0) * u(rng));
        const auto point = [&](double s) { return p0 + s * v; };
        const auto raster = [&](double s) {
            const glm::dvec3 p = point(s);
            return c + f * glm::dvec2(p.x / p.z, -p.y / p.z);
        };
        SweepPath path = SweepPath::through({raster(-0.5), point(-0.5).z}, {raster(0.0), p0.z}, {raster(0.5), point(0.5).z});
        path.setStretch(glm::dvec2(p0.z / point(-0.5).z), glm::dvec2(p0.z / point(0.5).z));
        const SweepPath flat{raster(0.5) - raster(-0.5), 0.5 * (raster(-0.5) + raster(0.5)) - raster(0.0)};
        for (int i = 0; i <= 20; ++i) {
            const double s = i / 20.0 - 0.5;
            // Rasters are ~1000 px: a few ulps of them.
            EXPECT_NEAR(glm::length(path.pivot + offsetAt(path, s) - raster(s)), 0.0, 1e-9) << trial << " s " << s;
            EXPECT_NEAR(stretchAt(path, s).x, p0.z / point(s).z, 1e-12) << trial;
            EXPECT_NEAR(stretchAt(path, s).y, p0.z / point(s).z, 1e-12) << trial;
            EXPECT_LE(glm::length(offsetAt(path, s)), path.reach() + 1e-9);
            raster_parabola = std::max(raster_parabola, glm::length(raster(0.0) + offsetAt(flat, s) - raster(s)));
        }
    }
    EXPECT_GT(raster_parabola, 10.0);  // what following the raster parabola would miss (px)
}

// sweptBounds holds every vertex at every position and is tight: its sides are the extremes of the moved
// bounds over the positions' span (the last comparison, on a dense grid of 20001 times, is within the
// grid's own error, quadratic in its step). Seeded random paths with bend, stretch and depth terms.
TEST(SweepPath, BoundsHoldEveryPositionAndAreTight) {
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
        const auto moved = [&](double s, const glm::dvec2& p) {
            return path.pivot + offsetAt(path, s) + stretchAt(path, s) * (p - path.pivot);
        };
        for (int m : {1, 2, 5, 17}) {
            const RasterBounds b = sweptBounds(q, path, m);
            for (int k = 0; k < m; ++k)
                for (int i = 0; i < q.n; ++i) {
                    const glm::dvec2 p = moved((k + 0.5) / m - 0.5, q.v[i]);
                    EXPECT_GE(p.x, b.lo.x - 1e-9);
                    EXPECT_GE(p.y, b.lo.y - 1e-9);
                    EXPECT_LE(p.x, b.hi.x + 1e-9);
                    EXPECT_LE(p.y, b.hi.y + 1e-9);
                }
            const double first = 0.5 / m - 0.5;
            glm::dvec2 lo(1e300), hi(-1e300);
            const RasterBounds box = q.bounds();
            for (int i = 0; i <= 20000; ++i) {
                const double s = m == 1 ? 0.0 : first + (-2.0 * first) * i / 20000.0;
                for (const glm::dvec2& corner : {box.lo, box.hi}) {
                    lo = glm::min(lo, moved(s, corner));
                    hi = glm::max(hi, moved(s, corner));
                }
            }
            EXPECT_NEAR(b.lo.x, lo.x, 1e-4) << trial << " m " << m;
            EXPECT_NEAR(b.lo.y, lo.y, 1e-4) << trial << " m " << m;
            EXPECT_NEAR(b.hi.x, hi.x, 1e-4) << trial << " m " << m;
            EXPECT_NEAR(b.hi.y, hi.y, 1e-4) << trial << " m " << m;
        }
    }
    EXPECT_GT(checked, 200);
}

// With a turning camera, SweepPath::through the unturned ends (the turn's inverse applied there) and the
// turn applied at each position follows a point exactly under camera translation and rotation, however
// far the camera turns. Projected and turned here by hand: camera coordinates R(s)^T (X - c(s)), R(s) a
// turn by 0.4 s rad about a random axis, c(s) linear; raster = (cx + f x / z, cy - f y / z), so the turn
// from s = 0 to s is K R(s)^T R(0) K^-1 with K = [f 0 cx; 0 -f cy; 0 0 1]. reach() and sweptBounds hold
// every position of a pixel-sized polygon (with their margins).
TEST(SweepPath, TurnsFollowATurningMovingCameraExactly) {
    std::mt19937 rng(20261125);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double f = 600.0;
    const glm::dvec2 centre(640.0, 360.0);
    glm::dmat3 K(1.0);
    K[0][0] = f;
    K[1][1] = -f;
    K[2] = glm::dvec3(centre, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        const glm::dvec3 axis = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        const glm::dvec3 c0(u(rng), u(rng), u(rng)), v(2.0 * u(rng), 2.0 * u(rng), 2.0 * u(rng));
        const glm::dvec3 x(4.0 * u(rng), 3.0 * u(rng), 12.0 + 2.0 * u(rng));
        const auto rotation = [&](double s) { return glm::mat3_cast(glm::angleAxis(0.4 * s, axis)); };
        const auto camera = [&](double s) { return glm::transpose(rotation(s)) * (x - (c0 + s * v)); };
        const auto raster = [&](double s) {
            const glm::dvec3 p = camera(s);
            return centre + f * glm::dvec2(p.x / p.z, -p.y / p.z);
        };
        const auto turn = [&](double s) { return K * glm::transpose(rotation(s)) * rotation(0.0) * glm::inverse(K); };
        SweepPath path = SweepPath::through({raster(-0.5), camera(-0.5).z}, {raster(0.0), camera(0.0).z},
                                            {raster(0.5), camera(0.5).z}, glm::inverse(turn(-0.5)), glm::inverse(turn(0.5)));
        for (int i = 0; i <= 20; ++i) {
            const double s = i / 20.0 - 0.5;
            const glm::dmat3 t = turn(s);
            glm::dvec2 offset, stretch;
            path.place(s, &t, offset, stretch);
            // Rasters ~1000 px: a few ulps of them.
            EXPECT_NEAR(glm::length(path.pivot + offset - raster(s)), 0.0, 1e-9) << trial << " s " << s;
        }
        const int m = 7;
        std::vector<glm::dmat3> turns;
        for (int k = 0; k < m; ++k) turns.push_back(turn((k + 0.5) / m - 0.5));
        path.turns = turns;
        path.setStretch(glm::dvec2(1.0 + 0.1 * u(rng), 1.0 + 0.1 * u(rng)), glm::dvec2(1.0 + 0.1 * u(rng), 1.0 + 0.1 * u(rng)));
        ConvexPolygon q = randomFragment(rng, glm::floor(path.pivot));
        const RasterBounds b = sweptBounds(q, path, m);
        for (int k = 0; k < m; ++k) {
            glm::dvec2 offset, stretch;
            path.place((k + 0.5) / m - 0.5, path.turnAt(k, m), offset, stretch);
            EXPECT_LE(glm::length(offset), path.reach()) << trial;
            for (int i = 0; i < q.n; ++i) {
                const glm::dvec2 p = path.pivot + offset + stretch * (q.v[i] - path.pivot);
                EXPECT_TRUE(p.x >= b.lo.x && p.y >= b.lo.y && p.x <= b.hi.x && p.y <= b.hi.y) << trial;
            }
        }
    }
}

// A surface turning away: the x stretch runs from 1 at s = -1/2 through 1 at 0 to -1 at 1/2, numerator
// 1 - 2 s - 4 s^2, which is 0 at s = (sqrt 5 - 1) / 4 = 0.309. Positions after that are left out, so
// the weights sum to the mean over positions of the square's stretched area, that numerator where it is
// positive and 0 after.
TEST(SweptFootprint, PositionsWhereTheSurfaceFacesAwayAreLeftOut) {
    ConvexPolygon square;
    for (glm::dvec2 v : {glm::dvec2(3, 5), glm::dvec2(4, 5), glm::dvec2(4, 6), glm::dvec2(3, 6)}) square.push(v);
    square.close();
    SweepPath path;
    path.chord = glm::dvec2(4.0, 0.0);
    path.pivot = glm::dvec2(3.5, 5.5);
    path.setStretch(glm::dvec2(1.0), glm::dvec2(-1.0, 1.0));
    const double root = (std::sqrt(5.0) - 1.0) / 4.0;
    for (int m : {1, 4, 7, 16}) {
        double expected = 0.0;
        for (int k = 0; k < m; ++k) {
            const double s = (k + 0.5) / m - 0.5;
            if (s < root) expected += (1.0 - 2.0 * s - 4.0 * s * s) / m;
        }
        double total = 0.0;
        for (const auto& [pixel, weight] : collect(square, path, m)) total += weight;
        EXPECT_NEAR(total, expected, 1e-12) << m;
    }
}

// With a clip, forEachSweptCell visits only the clip's cells and gives each the weight the unclipped call
// does: seeded random fragments stretched into polygons of up to 60 px (and axis-aligned rectangles,
// the separable path), random straight paths with a stretch, random clips inside, across and outside.
TEST(SweptFootprint, ClipVisitsOnlyItsCellsWithTheSameWeights) {
    std::mt19937 rng(20261129);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int trial = 0; trial < 300; ++trial) {
        ConvexPolygon q = randomFragment(rng, glm::dvec2(0.0));
        if (trial % 3 == 0) {  // an axis-aligned rectangle
            q.clear();
            for (glm::dvec2 v : {glm::dvec2(0.2, 0.1), glm::dvec2(0.9, 0.1), glm::dvec2(0.9, 1.0), glm::dvec2(0.2, 1.0)}) q.push(v);
        }
        const double scale = 1.0 + 30.0 * (1.0 + u(rng));
        for (int i = 0; i < q.n; ++i) q.v[i] = glm::dvec2(40.0, 30.0) + scale * q.v[i];
        SweepPath path;
        path.chord = 20.0 * glm::dvec2(u(rng), u(rng));
        path.pivot = glm::dvec2(40.0 + 10.0 * u(rng), 30.0 + 10.0 * u(rng));
        path.setStretch(glm::dvec2(1.0 + 0.5 * u(rng), 1.0), glm::dvec2(1.0, 1.0 + 0.5 * u(rng)));
        const int x0 = static_cast<int>(std::floor(60.0 * (1.0 + u(rng)))), y0 = static_cast<int>(std::floor(40.0 * (1.0 + u(rng))));
        const PixelBounds clip = PixelBounds::sized(x0, y0, 1 + static_cast<int>(20.0 * (1.0 + u(rng))), 1 + static_cast<int>(20.0 * (1.0 + u(rng))));
        const int m = 1 + trial % 5;
        Weights all, clipped;
        forEachSweptCell(q, path, m, [&](int x, int y, double w) {
            if (clip.contains(x, y)) all[{x, y}] += w;
        });
        forEachSweptCell(q, path, m, clip, [&](int x, int y, double w) {
            EXPECT_TRUE(clip.contains(x, y)) << trial << " visited " << x << "," << y << " outside " << toString(clip);
            clipped[{x, y}] += w;
        });
        ASSERT_EQ(clipped.size(), all.size()) << trial;
        // The clip cuts once where the unclipped call cuts cell by cell: rounding on coordinates ~100.
        for (const auto& [pixel, weight] : all) EXPECT_NEAR(clipped[pixel], weight, 1e-11) << trial;
    }
}

// A fragment near the camera plane is stretched to millions of pixels at some positions. With a clip
// (the tile's box) each position costs what it covers of the clip: a polygon far larger than a 16 x 12
// clip covers it whole at every position, weight 1 per cell (the unclipped call would cut about 1e13
// cells, so a regression hangs this test).
TEST(SweptFootprint, HugePolygonCostsWhatItCoversOfTheClip) {
    ConvexPolygon q;
    for (glm::dvec2 v : {glm::dvec2(-3e6, -2e6), glm::dvec2(4e6, -1e6), glm::dvec2(1e6, 5e6)}) q.push(v);
    q.close();
    SweepPath path;
    path.chord = glm::dvec2(7.0, -3.0);
    const PixelBounds clip = PixelBounds::sized(100, 50, 16, 12);
    for (int m : {1, 4}) {
        Weights w;
        forEachSweptCell(q, path, m, clip, [&](int x, int y, double weight) { w[{x, y}] += weight; });
        ASSERT_EQ(w.size(), clip.area()) << m;
        // Cuts at coordinates ~1e6 round at 1e-10 of a pixel.
        for (const auto& [pixel, weight] : w) EXPECT_NEAR(weight, 1.0, 1e-9) << m;
    }
}

}  // namespace clipblur
