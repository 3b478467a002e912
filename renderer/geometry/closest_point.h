#pragma once

#include <array>

#include <glm/vec2.hpp>

namespace clipblur {

// The point of the closed triangle `v` (either winding, possibly degenerate: a segment or a point)
// nearest to `x`; x itself when it lies inside or on an edge.
glm::dvec2 closestPointInTriangle(const std::array<glm::dvec2, 3>& v, const glm::dvec2& x);

}  // namespace clipblur
