#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace clipblur {

using TriangleIndices = std::array<std::uint32_t, 3>;

// One polygon face: indices into a position list, in winding order.
using PolygonFace = std::vector<std::uint32_t>;

// The face's vertices in its plane (Newell normal), counter-clockwise seen from the side the face's
// winding faces, so a non-degenerate face has positive signed area.
std::vector<glm::dvec2> projectFace(const std::vector<glm::dvec3>& positions, const PolygonFace& face);

// True when every turn of the projected polygon is a left turn (or straight) and it winds once.
bool isConvexPolygon(const std::vector<glm::dvec2>& polygon);

// Both produce n - 2 triangles of the face's winding for a simple polygon of n vertices, appended to
// `out`. Convex: arcs halved around a middle triangle, O(n); at most 2 log2(n) + 3 triangles meet at
// a vertex, where a fan from one vertex stacks all n - 2 slivers at that vertex.
void triangulateConvex(const PolygonFace& face, std::vector<TriangleIndices>& out);
// Any simple polygon by ear clipping, O(n^2): callers bound n. A polygon without an ear (self-crossing)
// still gives n - 2 triangles, clipped where no ear was found.
void triangulateByEarClipping(const std::vector<glm::dvec2>& polygon, const PolygonFace& face,
                              std::vector<TriangleIndices>& out);

}  // namespace clipblur
