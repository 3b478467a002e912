#pragma once

#include <vector>

#include "scene/job.h"

namespace clipblur {

// A shutter's weight over time as a camera's shutter has it: the piecewise-linear curve through
// `shutter.curve` (a box when the job gives none), in absolute frames for one frame, normalised so that
// its integral over [open, close] is 1. A renderer's pixel is the integral of coverage(t) x density(t).
class ShutterCurve {
public:
    ShutterCurve(const Shutter& shutter, int frame);

    // No curve, or every weight equal: the renderers keep their box-shutter code, bit for bit.
    bool box() const { return box_; }
    double open() const { return times_.front(); }
    double close() const { return times_.back(); }
    // The breakpoints, open and close included, and the curve's unnormalised weight at each.
    const std::vector<double>& times() const { return times_; }
    const std::vector<double>& weights() const { return weights_; }

    // Unnormalised weight at t (linear between breakpoints, 0 outside [open, close]).
    double weightAt(double t) const;
    // Integral of the normalised density over [a, b], within the shutter.
    double mass(double a, double b) const;
    // The time at which the normalised integral from open reaches u in [0, 1]: the inverse of the CDF,
    // a quadratic per piece solved in closed form. A box gives open + u (close - open).
    double timeAt(double u) const;

private:
    std::vector<double> times_, weights_;
    std::vector<double> cumulative_;  // unnormalised integral from open to each breakpoint
    double total_ = 0.0;
    bool box_ = true;
};

}  // namespace clipblur
