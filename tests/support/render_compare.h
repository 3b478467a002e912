#pragma once

#include <vector>

#include "renderer/render.h"

namespace clipblur::testing {

// Mean over R, G, B of the pixels in `mask` (all of them when it is empty) of (a - ref)^2, with ref = b,
// or the mean of b and c when c is given (two stochastic renders with independent seeds).
double meanSquaredDifference(const RenderResult& a, const RenderResult& b, const RenderResult* c = nullptr,
                             const std::vector<bool>& mask = {});

// The channel-by-channel mean of two renders of one frame.
RenderResult averaged(const RenderResult& a, const RenderResult& b);

}  // namespace clipblur::testing
