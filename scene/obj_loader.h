#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "scene/scene.h"

namespace clipblur {

inline constexpr std::uintmax_t kMaxObjFileBytes = std::uintmax_t{512} << 20;
// Non-convex faces are ear-clipped in O(n^2); convex faces of any size are split in O(n).
inline constexpr std::size_t kMaxConcaveFaceVertices = 1024;

// Positions and triangles of every `v` and `f` statement of a Wavefront OBJ file, merged into one mesh
// (other statements, normals, texture coordinates and materials ignored). Faces keep their winding;
// polygons are split by scene/polygon_triangulation.h. Coordinates must be finite numbers within
// kMaxCoordinate, and faces need at least three vertices that exist (1-based, or negative: relative to
// the vertices read so far). Errors in the file are located file:line:col in it and name `ref`, where
// the job refers to it; errors about the file as a whole are located at `ref`. Meshes above
// max_triangles are refused.
Mesh loadObjMesh(const std::filesystem::path& file, const FileLoc& ref, std::uint64_t max_triangles);

// The same, from text already in memory; `name` is the file name in locations.
Mesh parseObjMesh(const std::string& text, const std::string& name, const FileLoc& ref,
                  std::uint64_t max_triangles);

}  // namespace clipblur
