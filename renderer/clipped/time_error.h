#pragma once

#include <cmath>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

namespace clipblur {

// The render's own estimate of its time-sampling error (stats `estimated_error`), by Richardson
// extrapolation from a nested coarser rule that reuses the samples the render already takes.
//
// m equally spaced midpoint samples of an interval (sweep positions, or point subframes) are the midpoint
// rule Q_h of step h. The middle sample of each group of three is the midpoint rule Q_3h of step 3h over
// the same interval; samples left over after the last whole group keep their weight (so Q_3h stays a
// composite midpoint rule of the whole interval, its cells not all equal). It costs no geometry, only a
// second weighted sum. With E(h) = C h^p, Q_3h - Q_h = (3^p - 1) E(h).
//
// p = 2: a pixel's box-filtered value over time is continuous and piecewise smooth, with kinks where an
// edge enters or leaves it, and the midpoint rule's error at a kink of slope jump D is D h^2 g(u), g in
// [0, 1/8] by where the kink falls in its cell. An order measured from a third, 9h rule describes the
// coarser pair (3h, 9h), where positions are pixels apart and a pixel's value is nearly a step (p ~ 1):
// at 1 px spacing it under-estimated p by 0.5 to 1.5 on the bench scenes (docs/performance.md).
// Fewer than 3 samples give no coarser rule: their difference is 0, as it is for a still surface.
struct NestedRule {
    std::vector<double> to3;  // per sample: its weight in Q_3h minus its weight in Q_h (in units of 1 / m)

    explicit NestedRule(int samples);
};

constexpr double kTimeErrorOrder = 2.0;

// Q_3h - Q_h per unit of the fine rule's error E(h): 3^p - 1.
inline double levelsPerError() { return std::pow(3.0, kTimeErrorOrder) - 1.0; }

// Per pixel Q_3h - Q_h in R, G, B and covered area. Floats: an estimate needs no more, and a film's
// worth of them stays 16 bytes a pixel.
using LevelDifference = glm::vec4;

// The RMS over R, G and B of every pixel's estimated fine-level error, (Q_3h - Q_h) / (3^p - 1).
double estimateTimeError(std::span<const LevelDifference> pixels);

}  // namespace clipblur
