#pragma once

#include <vector>

namespace clipblur {

// One object's share of a pixel: the fraction of pixel area x shutter time in which it is the
// visible surface.
struct ObjectShare {
    int object = 0;
    double coverage = 0.0;
};

// Per pixel of the render window (row-major, like Image channels), the objects seen there in
// increasing object order; their coverages sum to the pixel's alpha. Empty unless the job asks for ID
// mattes (output.cryptomatte).
struct ObjectCoverage {
    std::vector<std::vector<ObjectShare>> pixels;
};

// Adds `amount` to `object`'s share, keeping `shares` in increasing object order (so the sum, and so
// the result, does not depend on the order objects are met in).
void addShare(std::vector<ObjectShare>& shares, int object, double amount);

}  // namespace clipblur
