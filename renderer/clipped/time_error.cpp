#include "renderer/clipped/time_error.h"

#include <algorithm>
#include <cmath>

namespace clipblur {

NestedRule::NestedRule(int samples) {
    const int m = std::max(1, samples);
    to3.assign(static_cast<std::size_t>(m), 0.0);
    for (int g = 0; g < m / 3; ++g)
        for (int k = 0; k < 3; ++k) to3[static_cast<std::size_t>(3 * g + k)] = k == 1 ? 2.0 : -1.0;
}

double estimateTimeError(std::span<const LevelDifference> pixels) {
    if (pixels.empty()) return 0.0;
    double sum = 0.0;
    for (const LevelDifference& p : pixels)
        for (int c = 0; c < 3; ++c) sum += double(p[c]) * p[c];
    return std::sqrt(sum / (3.0 * static_cast<double>(pixels.size()))) / levelsPerError();
}

}  // namespace clipblur
