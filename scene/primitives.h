#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace clipblur {

// Built-in meshes, centred on the origin in object space. Winding convention: a triangle (a, b, c)
// faces along cross(b - a, c - a); closed meshes face outward, flat ones face +y.

// A quad in the xz-plane, size.x by size.y (along x and z).
Mesh makeQuad(const glm::dvec2& size);

// The same quad split into nx by nz cells, two triangles each, vertices shared.
Mesh makeGrid(const glm::dvec2& size, int nx, int nz);
std::uint64_t gridTriangleCount(int nx, int nz);

// An axis-aligned box of the given edge lengths: 8 shared vertices, 12 triangles, closed.
Mesh makeBox(const glm::dvec3& size);

// A UV sphere of the given radius with `segments` longitudes and segments/2 latitude bands (at
// least 2); the poles are single vertices so the mesh is closed.
Mesh makeSphere(double radius, int segments);
std::uint64_t sphereTriangleCount(int segments);

}  // namespace clipblur
