#pragma once

#include <vector>

namespace clipblur {

// One object's share of a pixel: the fraction of pixel area x shutter time in which it is the
// visible surface.
struct ObjectShare {
    int object = 0;
    double coverage = 0.0;
};

// One pixel's shares in increasing object order.
using ObjectShares = std::vector<ObjectShare>;

// Per pixel of the render window (row-major, like Image channels), the objects seen there in
// increasing object order; their coverages sum to the pixel's alpha. Empty unless the job asks for ID
// mattes (output.cryptomatte).
struct ObjectCoverage {
    std::vector<ObjectShares> pixels;
};

// Adds `amount` to `object`'s share, keeping `shares` in increasing object order (so the sum, and so
// the result, does not depend on the order objects are met in).
void addShare(ObjectShares& shares, int object, double amount);

// Adds scale x every share of `from` to `to`, in `from`'s order: callers reduce in a fixed order, so
// the result is the same on any number of threads.
void addShares(ObjectShares& to, const ObjectShares& from, double scale);

}  // namespace clipblur
