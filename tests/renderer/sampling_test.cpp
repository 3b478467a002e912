#include <cmath>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/sampling/hash_rng.h"
#include "renderer/sampling/pixel_samples.h"
#include "renderer/tiles.h"

namespace clipblur {

TEST(HashRng, UniformMeanAndVarianceMatchTheUniformDistribution) {
    // n draws spread over many keys (pixels) and indices, as the renderer uses them.
    const int n = 1 << 20;
    double sum = 0.0;
    double sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double u = HashRng::forKey(42, 3, static_cast<std::uint64_t>(i / 16)).child(i % 16).uniform(i % 3);
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
        sum += u;
        sum2 += u * u;
    }
    const double mean = sum / n;
    const double var = sum2 / n - mean * mean;
    // Standard error of the mean sqrt(1/12/n) ~ 2.8e-4, of the variance sqrt(1/180/n) ~ 7.3e-5; allow 5 sigma.
    EXPECT_NEAR(mean, 0.5, 5 * std::sqrt(1.0 / 12.0 / n));
    EXPECT_NEAR(var, 1.0 / 12.0, 5 * std::sqrt(1.0 / 180.0 / n));
}

TEST(HashRng, NeighbouringStreamsAreUncorrelated) {
    // Lag-one correlation between streams of adjacent pixels; for independent uniforms its standard
    // error is 1/sqrt(n), allow 5 sigma.
    const int n = 1 << 18;
    double sxy = 0.0;
    double sx = 0.0;
    double sy = 0.0;
    double sxx = 0.0;
    double syy = 0.0;
    for (int i = 0; i < n; ++i) {
        const double x = HashRng::forKey(1, 0, static_cast<std::uint64_t>(i)).uniform(0);
        const double y = HashRng::forKey(1, 0, static_cast<std::uint64_t>(i) + 1).uniform(0);
        sx += x;
        sy += y;
        sxy += x * y;
        sxx += x * x;
        syy += y * y;
    }
    const double cov = sxy / n - (sx / n) * (sy / n);
    const double r = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
    EXPECT_LT(std::fabs(r), 5.0 / std::sqrt(static_cast<double>(n)));
}

TEST(HashRng, BelowStaysInRangeAndHitsEveryValue) {
    const HashRng rng = HashRng::forKey(9, 9);
    std::vector<int> hist(7, 0);
    for (int i = 0; i < 7000; ++i) ++hist[rng.below(static_cast<std::uint64_t>(i), 7)];
    // Each bin expects 1000 with sd ~29; 5 sigma.
    for (int c : hist) EXPECT_NEAR(c, 1000, 150);
}

TEST(PixelSamples, EveryCellAndEveryFineStratumHoldsOneSample) {
    std::vector<SpaceTimeSample> samples;
    std::vector<std::uint32_t> scratch;
    for (int count = 1; count <= 70; ++count) {
        generatePixelSamples(HashRng::forKey(5, 1, static_cast<std::uint64_t>(count)), count, samples, scratch);
        ASSERT_EQ(samples.size(), static_cast<std::size_t>(count));
        const StrataShape shape = strataShape(count);
        ASSERT_EQ(shape.columns * shape.rows, count);
        std::set<int> fx, fy, ft, cells;
        for (const auto& s : samples) {
            ASSERT_GE(s.x, 0.0);
            ASSERT_LT(s.x, 1.0);
            ASSERT_GE(s.y, 0.0);
            ASSERT_LT(s.y, 1.0);
            ASSERT_GE(s.time, 0.0);
            ASSERT_LT(s.time, 1.0);
            fx.insert(static_cast<int>(s.x * count));
            fy.insert(static_cast<int>(s.y * count));
            ft.insert(static_cast<int>(s.time * count));
            cells.insert(static_cast<int>(s.x * shape.columns) * 1000 + static_cast<int>(s.y * shape.rows));
        }
        EXPECT_EQ(fx.size(), static_cast<std::size_t>(count)) << count;
        EXPECT_EQ(fy.size(), static_cast<std::size_t>(count)) << count;
        EXPECT_EQ(ft.size(), static_cast<std::size_t>(count)) << count;
        EXPECT_EQ(cells.size(), static_cast<std::size_t>(count)) << count;
    }
}

TEST(PixelSamples, SameKeySamePatternOtherPixelOtherPattern) {
    std::vector<SpaceTimeSample> a, b, c;
    std::vector<std::uint32_t> scratch;
    generatePixelSamples(HashRng::forKey(1, 2, 3), 16, a, scratch);
    generatePixelSamples(HashRng::forKey(1, 2, 3), 16, b, scratch);
    generatePixelSamples(HashRng::forKey(1, 2, 4), 16, c, scratch);
    int same = 0;
    for (int i = 0; i < 16; ++i) {
        EXPECT_EQ(a[i].x, b[i].x);
        EXPECT_EQ(a[i].time, b[i].time);
        same += a[i].x == c[i].x;
    }
    EXPECT_EQ(same, 0);
}

TEST(TileGrid, TilesCoverEveryPixelExactlyOnce) {
    for (int size : {1, 7, 32}) {
        const int w = 45;
        const int h = 13;
        const TileGrid grid(w, h, size);
        std::vector<int> hits(static_cast<std::size_t>(w * h), 0);
        for (int i = 0; i < grid.count(); ++i) {
            const PixelBounds t = grid.tile(i);
            EXPECT_GT(t.width(), 0);
            EXPECT_GT(t.height(), 0);
            for (int y = t.y0; y < t.y1; ++y)
                for (int x = t.x0; x < t.x1; ++x) ++hits[static_cast<std::size_t>(y * w + x)];
        }
        for (int v : hits) ASSERT_EQ(v, 1);
    }
}

}  // namespace clipblur
