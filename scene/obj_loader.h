#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "scene/scene.h"

namespace clipblur {

inline constexpr std::uintmax_t kMaxObjFileBytes = std::uintmax_t{512} << 20;

// Positions and triangles of every shape in a Wavefront OBJ file, merged into one mesh (polygons
// triangulated by tinyobjloader, winding kept; normals, texture coordinates and materials ignored). `ref` locates the
// reference in the job file for errors; meshes above max_triangles are refused.
Mesh loadObjMesh(const std::filesystem::path& file, const FileLoc& ref, std::uint64_t max_triangles);

// The same, from text already in memory; `name` is used in messages.
Mesh parseObjMesh(const std::string& text, const std::string& name, const FileLoc& ref,
                  std::uint64_t max_triangles);

}  // namespace clipblur
