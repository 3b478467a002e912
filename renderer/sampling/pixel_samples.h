#pragma once

#include <cstdint>
#include <vector>

#include "renderer/sampling/hash_rng.h"

namespace clipblur {

// One space-time sample inside a pixel: offset in [0,1)^2 from the pixel corner, time in [0,1) over
// the shutter.
struct SpaceTimeSample {
    double x = 0.0;
    double y = 0.0;
    double time = 0.0;
};

// Grid shape m x n = count with m the largest divisor of count not above sqrt(count).
struct StrataShape {
    int columns = 1;
    int rows = 1;
};
StrataShape strataShape(int count);

// Fills `out` with `count` samples for one pixel:
//  - space: multi-jittered (Chiu, Shirley & Wang 1994): one sample per cell of the m x n grid and one
//    per each of the `count` fine strata along x and along y, the sub-cell positions shuffled;
//  - time: one sample per each of `count` equal time strata, the strata shuffled against space so that
//    time does not correlate with position (a Latin hypercube in time).
// Every random number comes from `pixel` (the stream of (seed, frame, pixel)); sample s's jitter from
// pixel.child(s), so the pattern is independent of threads and of tile order.
void generatePixelSamples(const HashRng& pixel, int count, std::vector<SpaceTimeSample>& out,
                          std::vector<std::uint32_t>& scratch);

}  // namespace clipblur
