#include "renderer/sampling/pixel_samples.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace clipblur {

StrataShape strataShape(int count) {
    int m = static_cast<int>(std::sqrt(static_cast<double>(count)));
    while (m > 1 && count % m != 0) --m;
    m = std::max(m, 1);
    return {m, count / m};
}

namespace {

// Streams reserved inside a pixel's stream for the permutations; sample streams use child(s) with
// s < count, these use indices no sample count can reach.
constexpr std::uint64_t kTimePermutation = 0xffffffff00000001ULL;
constexpr std::uint64_t kColumnPermutations = 0xffffffff00010000ULL;
constexpr std::uint64_t kRowPermutations = 0xffffffff80000000ULL;

// (k + u) / count can round up to 1.0 for the last stratum; keep samples inside [0, 1).
double inUnit(double v) { return std::min(v, 0x1.fffffffffffffp-1); }

void shuffle(const HashRng& rng, std::uint32_t* values, std::uint32_t n) {
    std::iota(values, values + n, 0u);
    for (std::uint32_t i = n; i > 1; --i) {
        const std::uint32_t j = rng.below(i, i);
        std::swap(values[i - 1], values[j]);
    }
}

}  // namespace

void generatePixelSamples(const HashRng& pixel, int count, std::vector<SpaceTimeSample>& out,
                          std::vector<std::uint32_t>& scratch) {
    const auto [m, n] = strataShape(count);
    const auto total = static_cast<std::uint32_t>(count);
    out.resize(total);
    // scratch: time permutation (count), then per column a permutation of rows' sub-strata (m * n),
    // then per row a permutation of columns' sub-strata (n * m).
    scratch.resize(3 * static_cast<std::size_t>(total));
    std::uint32_t* time_perm = scratch.data();
    std::uint32_t* x_sub = time_perm + total;  // x_sub[i * n + j]: fine x stratum of cell (i, j) within column i
    std::uint32_t* y_sub = x_sub + total;      // y_sub[j * m + i]: fine y stratum of cell (i, j) within row j
    shuffle(pixel.child(kTimePermutation), time_perm, total);
    for (int i = 0; i < m; ++i) shuffle(pixel.child(kColumnPermutations + i), x_sub + i * n, n);
    for (int j = 0; j < n; ++j) shuffle(pixel.child(kRowPermutations + j), y_sub + j * m, m);

    for (std::uint32_t s = 0; s < total; ++s) {
        const int i = static_cast<int>(s % m);  // column
        const int j = static_cast<int>(s / m);  // row
        const HashRng rng = pixel.child(s);
        // Column i holds fine x strata i*n .. i*n+n-1, one per row; row j holds fine y strata j*m .. j*m+m-1.
        out[s].x = inUnit((i * n + x_sub[i * n + j] + rng.uniform(0)) / count);
        out[s].y = inUnit((j * m + y_sub[j * m + i] + rng.uniform(1)) / count);
        out[s].time = inUnit((time_perm[s] + rng.uniform(2)) / count);
    }
}

}  // namespace clipblur
