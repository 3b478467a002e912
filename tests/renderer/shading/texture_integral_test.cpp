#include "renderer/shading/texture_integral.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace clipblur {

namespace {

TexelLevel randomLevel(int w, int h, std::mt19937_64& rng) {
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    TexelLevel level{w, h, {}};
    for (int k = 0; k < 3 * w * h; ++k) level.rgb.push_back(value(rng));
    return level;
}

// A convex polygon through `n` points at sorted random angles on an ellipse about `centre`, counter-
// clockwise in (s, t).
ConvexPolygon randomPolygon(const glm::dvec2& centre, const glm::dvec2& radii, int n, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
    std::vector<double> angles;
    for (int k = 0; k < n; ++k) angles.push_back(angle(rng));
    std::sort(angles.begin(), angles.end());
    ConvexPolygon p;
    for (double a : angles) p.push(centre + radii * glm::dvec2(std::cos(a), std::sin(a)));
    p.close();
    return p;
}

// The test's own periodic bilinear image of `level` along a row: at texel-centre coordinate (u, v).
double bilinear(const TexelLevel& level, double u, double v, int k) {
    const auto wrap = [](long long i, int n) { return static_cast<int>(((i % n) + n) % n); };
    const double fu = std::floor(u), fv = std::floor(v);
    const int i0 = wrap(static_cast<long long>(fu), level.width), i1 = wrap(static_cast<long long>(fu) + 1, level.width);
    const int j0 = wrap(static_cast<long long>(fv), level.height), j1 = wrap(static_cast<long long>(fv) + 1, level.height);
    const auto t = [&](int i, int j) { return double(level.rgb[static_cast<std::size_t>(3 * (j * level.width + i) + k)]); };
    const double x = u - fu, y = v - fv;
    return (1 - y) * ((1 - x) * t(i0, j0) + x * t(i1, j0)) + y * ((1 - x) * t(i0, j1) + x * t(i1, j1));
}

// The mean over `st` of the bilinear image by rows: `rows` midpoint rows in t, and along each row the
// polygon's chord, over which the image is piecewise linear in s (breaks at texel centres), integrated
// exactly by the trapezoid rule on its breaks. The only approximation is the midpoint rule in t, whose
// error is O(h^2) per unit length (the row integral is continuous with piecewise-continuous derivatives).
glm::dvec3 rowQuadrature(const TexelLevel& level, const ConvexPolygon& st, int rows, const AffineWeight& weight = {}) {
    double t_lo = INFINITY, t_hi = -INFINITY;
    for (int k = 0; k < st.n; ++k) {
        t_lo = std::min(t_lo, st.v[k].y);
        t_hi = std::max(t_hi, st.v[k].y);
    }
    const double h = (t_hi - t_lo) / rows;
    glm::dvec3 sum(0.0);
    double area = 0.0;
    for (int r = 0; r < rows; ++r) {
        const double t = t_lo + (r + 0.5) * h;
        double s_lo = INFINITY, s_hi = -INFINITY;
        for (int k = 0; k < st.n; ++k) {
            const glm::dvec2 a = st.v[k], b = st.v[(k + 1) % st.n];
            if ((a.y - t) * (b.y - t) > 0.0 || a.y == b.y) continue;
            const double s = a.x + (t - a.y) / (b.y - a.y) * (b.x - a.x);
            s_lo = std::min(s_lo, s);
            s_hi = std::max(s_hi, s);
        }
        if (!(s_hi > s_lo)) continue;
        // The weight is affine along the row, so the image times it is quadratic between breaks: Simpson's
        // rule is exact there, as the trapezoid rule is for the image alone.
        const auto rho = [&](double s) { return 1.0 + weight.slope.x * (s - weight.at.x) + weight.slope.y * (t - weight.at.y); };
        area += 0.5 * (rho(s_lo) + rho(s_hi)) * (s_hi - s_lo) * h;
        const double v = t * level.height - 0.5;
        const double u_lo = s_lo * level.width - 0.5, u_hi = s_hi * level.width - 0.5;
        std::vector<double> breaks{u_lo};
        for (double u = std::floor(u_lo) + 1.0; u < u_hi; u += 1.0) breaks.push_back(u);
        breaks.push_back(u_hi);
        const auto f = [&](double u, int k) { return bilinear(level, u, v, k) * rho((u + 0.5) / level.width); };
        for (int k = 0; k < 3; ++k)
            for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
                const double mid = 0.5 * (breaks[b] + breaks[b + 1]);
                sum[k] += (f(breaks[b], k) + 4.0 * f(mid, k) + f(breaks[b + 1], k)) / 6.0 *
                          (breaks[b + 1] - breaks[b]) / level.width * h;
            }
    }
    return sum / area;
}

// The area centroid by a triangle fan about the first vertex, independent of the code under test.
glm::dvec2 fanCentroid(const ConvexPolygon& p) {
    glm::dvec2 sum(0.0);
    double area = 0.0;
    for (int k = 1; k + 1 < p.n; ++k) {
        const glm::dvec2 a = p.v[k] - p.v[0], b = p.v[k + 1] - p.v[0];
        const double w = 0.5 * (a.x * b.y - a.y * b.x);
        sum += w * (p.v[0] + p.v[k] + p.v[k + 1]) / 3.0;
        area += w;
    }
    return sum / area;
}

ConvexPolygon rectangle(const glm::dvec2& lo, const glm::dvec2& hi) {
    ConvexPolygon p;
    for (const glm::dvec2& v : {lo, glm::dvec2(hi.x, lo.y), hi, glm::dvec2(lo.x, hi.y)}) p.push(v);
    return p;
}

}  // namespace

// Every texel the same colour: any polygon, of either orientation, reads that colour (to rounding).
TEST(TextureIntegral, ConstantTextureGivesTheConstant) {
    std::mt19937_64 rng(11);
    TexelLevel level{5, 3, {}};
    for (int k = 0; k < 15; ++k) level.rgb.insert(level.rgb.end(), {0.25f, 0.5f, 0.875f});
    for (int trial = 0; trial < 50; ++trial) {
        ConvexPolygon p = randomPolygon({1.3, -0.7}, {0.9, 0.4}, 3 + trial % 9, rng);
        if (trial % 2) std::reverse(p.v.begin(), p.v.begin() + p.n);
        const glm::dvec3 got = bilinearMean(level, p);
        EXPECT_NEAR(got.x, 0.25, 1e-12);
        EXPECT_NEAR(got.y, 0.5, 1e-12);
        EXPECT_NEAR(got.z, 0.875, 1e-12);
    }
}

// Texels affine in (i, j): away from the wrap the bilinear image is that affine function of (s, t), whose
// mean over a polygon is its value at the area centroid. 1e-6: the texels are floats (rounding 1e-7).
TEST(TextureIntegral, LinearRampGivesTheValueAtTheCentroid) {
    const int w = 16, h = 8;
    TexelLevel level{w, h, {}};
    const auto ramp = [](double i, double j, int k) { return 0.1 + 0.03 * (k + 1) * i + 0.05 * j; };
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            for (int k = 0; k < 3; ++k) level.rgb.push_back(static_cast<float>(ramp(i, j, k)));
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> where(0.3, 0.7);
    for (int trial = 0; trial < 50; ++trial) {
        // Within texel-centre coordinates 1.1 .. 13.9 and 0.7 .. 6.3: no cell reads across the wrap.
        const ConvexPolygon p = randomPolygon({where(rng), where(rng)}, {0.2, 0.15}, 3 + trial % 10, rng);
        const glm::dvec2 c = fanCentroid(p);
        const glm::dvec3 got = bilinearMean(level, p);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(got[k], ramp(c.x * w - 0.5, c.y * h - 0.5, k), 1e-6) << trial << " " << k;
    }
}

// Random polygons, a few texels to many, over a random 7 x 5 image, against rowQuadrature with 4000
// rows: its midpoint error is about h^2/24 times the row integral's second derivative (h = extent/4000,
// the derivative of order texels^2 per unit), measured at most 1e-7 here; 1e-6 leaves room for that, while
// reading a texel off by one or a transposed cell misses by 1e-2 or more.
TEST(TextureIntegral, RandomPolygonsMatchARowQuadrature) {
    std::mt19937_64 rng(13);
    const TexelLevel level = randomLevel(7, 5, rng);
    std::uniform_real_distribution<double> centre(-1.0, 2.0), radius(0.05, 0.6);
    for (int trial = 0; trial < 20; ++trial) {
        const ConvexPolygon p = randomPolygon({centre(rng), centre(rng)}, {radius(rng), radius(rng)}, 3 + trial % 10, rng);
        const glm::dvec3 got = bilinearMean(level, p);
        const glm::dvec3 want = rowQuadrature(level, p, 4000);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], 1e-6) << trial << " " << k;
    }
}

// The same with a weight affine in (s, t) (the raster Jacobian's, linearised), varying by up to +-40%
// over the polygon: the weighted mean against the weighted row quadrature, same tolerance and argument.
TEST(TextureIntegral, WeightedMeansMatchARowQuadrature) {
    std::mt19937_64 rng(18);
    const TexelLevel level = randomLevel(7, 5, rng);
    std::uniform_real_distribution<double> centre(-1.0, 2.0), radius(0.05, 0.6), direction(-1.0, 1.0);
    for (int trial = 0; trial < 20; ++trial) {
        const glm::dvec2 c(centre(rng), centre(rng)), r(radius(rng), radius(rng));
        const ConvexPolygon p = randomPolygon(c, r, 3 + trial % 10, rng);
        const AffineWeight weight{c, 0.4 * glm::dvec2(direction(rng), direction(rng)) / glm::length(r)};
        const glm::dvec3 got = bilinearMean(level, p, weight);
        const glm::dvec3 want = rowQuadrature(level, p, 4000, weight);
        const glm::dvec3 plain = bilinearMean(level, p);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], 1e-6) << trial << " " << k;
        EXPECT_GT(glm::length(got - plain), 1e-4) << trial;  // the weight matters at this size
    }
}

// A polygon across the seam s = 0 (and t = 0) reads both sides of the periodic image: it matches the row
// quadrature (which wraps texels on its own) and the same polygon moved by whole periods.
TEST(TextureIntegral, PieceStraddlingTheWrapSeam) {
    std::mt19937_64 rng(14);
    const TexelLevel level = randomLevel(6, 4, rng);
    const ConvexPolygon p = randomPolygon({0.02, -0.03}, {0.15, 0.2}, 7, rng);
    const glm::dvec3 got = bilinearMean(level, p);
    const glm::dvec3 want = rowQuadrature(level, p, 4000);
    ConvexPolygon moved = p;
    for (int k = 0; k < moved.n; ++k) moved.v[k] += glm::dvec2(3.0, -2.0);
    const glm::dvec3 shifted = bilinearMean(level, moved);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(got[k], want[k], 1e-6) << k;
        EXPECT_NEAR(got[k], shifted[k], 1e-12) << k;
    }
}

// A rectangle on texel centres, 10 x 6 cells at level 0: the bilinear image over one whole cell averages
// to the mean of its four texels, so the rectangle's mean is the mean of those cell means. The whole
// period [0, 1)^2 counts every texel four times: the image's mean.
TEST(TextureIntegral, ManyTexelsAtLevelZeroEqualTheCellSum) {
    std::mt19937_64 rng(15);
    const int w = 16, h = 12;
    const TexelLevel level = randomLevel(w, h, rng);
    const auto t = [&](int i, int j, int k) {
        return double(level.rgb[static_cast<std::size_t>(3 * (((j + h) % h) * w + (i + w) % w) + k)]);
    };
    const int i0 = 3, j0 = 4, n = 10, m = 6;
    const glm::dvec3 got = bilinearMean(level, rectangle({(i0 + 0.5) / w, (j0 + 0.5) / h}, {(i0 + n + 0.5) / w, (j0 + m + 0.5) / h}));
    const glm::dvec3 whole = bilinearMean(level, rectangle({0.0, 0.0}, {1.0, 1.0}));
    for (int k = 0; k < 3; ++k) {
        double cells = 0.0, texels = 0.0;
        for (int j = j0; j < j0 + m; ++j)
            for (int i = i0; i < i0 + n; ++i) cells += (t(i, j, k) + t(i + 1, j, k) + t(i, j + 1, k) + t(i + 1, j + 1, k)) / 4.0;
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) texels += t(i, j, k);
        EXPECT_NEAR(got[k], cells / (n * m), 1e-12) << k;
        EXPECT_NEAR(whole[k], texels / (w * h), 1e-12) << k;
    }
}

// Each level is the box average of the one above: every level keeps the image's mean, a 4 x 4 image's
// next level holds its 2 x 2 blocks' means, and odd sides (5 x 3 -> 2 x 1) weigh the texel a coarse
// texel splits by the half it covers.
TEST(TextureIntegral, PyramidLevelsAreBoxAverages) {
    std::mt19937_64 rng(16);
    const TexelLevel square = randomLevel(4, 4, rng);
    const TexelPyramid even({square.width, square.height, square.rgb});
    ASSERT_EQ(even.levels(), 3);
    const TexelLevel& half = even.level(1);
    ASSERT_EQ(half.width, 2);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i)
            for (int k = 0; k < 3; ++k) {
                const double want = (square.texel(2 * i, 2 * j)[k] + square.texel(2 * i + 1, 2 * j)[k] +
                                     square.texel(2 * i, 2 * j + 1)[k] + square.texel(2 * i + 1, 2 * j + 1)[k]) / 4.0;
                EXPECT_NEAR(half.texel(i, j)[k], want, 1e-6);
            }
    const TexelLevel odd = randomLevel(5, 3, rng);
    const TexelPyramid pyramid({odd.width, odd.height, odd.rgb});
    ASSERT_EQ(pyramid.level(1).width, 2);
    ASSERT_EQ(pyramid.level(1).height, 1);
    double mean = 0.0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 5; ++i) mean += odd.texel(i, j)[0] / 15.0;
    double left = 0.0;  // texels 0, 1 and half of 2 of each row
    for (int j = 0; j < 3; ++j) left += (odd.texel(0, j)[0] + odd.texel(1, j)[0] + 0.5 * odd.texel(2, j)[0]) / 7.5;
    EXPECT_NEAR(pyramid.level(1).texel(0, 0)[0], left, 1e-6);
    for (int l = 0; l < pyramid.levels(); ++l) {
        const TexelLevel& level = pyramid.level(l);
        double sum = 0.0;
        for (int j = 0; j < level.height; ++j)
            for (int i = 0; i < level.width; ++i) sum += level.texel(i, j)[0];
        EXPECT_NEAR(sum / (level.width * level.height), mean, 1e-6) << l;
    }
}

// The level a polygon is integrated on: the finest where area + perimeter / 2 + 1, in that level's texels,
// is at most the budget (32). On a 64 x 32 image a 0.5 x 0.1 rectangle is 32 x 3.2 texels at level 0
// (138.6), 16 x 1.6 at level 1 (44.2) and 8 x 0.8 at level 2 (16.2); a strip 0.5 x 0.002 of the same
// length is 35.1 at level 0 and 17.5 at level 1: it stays a level finer than its bounding box would put
// it. A polygon within a texel stays at level 0; one spanning many periods reaches the 1 x 1 level, the
// image's mean.
TEST(TextureIntegral, LevelTouchesAtMostTheCellBudget) {
    std::mt19937_64 rng(17);
    const TexelLevel image = randomLevel(64, 32, rng);
    const TexelPyramid pyramid({image.width, image.height, image.rgb});
    EXPECT_EQ(integralLevel(pyramid, rectangle({0.1, 0.1}, {0.6, 0.2}), 32.0), 2);
    EXPECT_EQ(integralLevel(pyramid, rectangle({0.1, 0.1}, {0.6, 0.102}), 32.0), 1);
    EXPECT_EQ(integralLevel(pyramid, rectangle({0.1, 0.1}, {0.11, 0.11}), 32.0), 0);
    const ConvexPolygon huge = rectangle({-3.0, -2.0}, {5.0, 7.0});
    const TexelLevel& last = pyramid.level(pyramid.levels() - 1);
    ASSERT_EQ(integralLevel(pyramid, huge, 32.0), pyramid.levels() - 1);
    EXPECT_EQ(last.width * last.height, 1);
    EXPECT_EQ(textureMean(pyramid, huge).x, last.rgb[0]);
}

}  // namespace clipblur
