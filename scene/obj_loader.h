#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace clipblur {

inline constexpr std::uintmax_t kMaxObjFileBytes = std::uintmax_t{512} << 20;
// Non-convex faces are ear-clipped in O(n^2); convex faces of any size are split in O(n).
inline constexpr std::size_t kMaxConcaveFaceVertices = 1024;

// The polygon faces of an OBJ file as written, before triangulation: vertex indices (0-based) of
// every face in file order, face f being indices[starts[f]] up to the next start. This, not the
// triangles, is what a deformation key shares with its object: how a face is split depends on its
// shape, which changes between keys.
struct ObjFaces {
    std::vector<std::uint32_t> indices;
    std::vector<std::size_t> starts;

    bool operator==(const ObjFaces&) const = default;
};

// Positions and triangles of every `v` and `f` statement of a Wavefront OBJ file, merged into one mesh,
// with the corner normals (`vn`) and texture coordinates (`vt`) that `f v/vt/vn` names (materials
// ignored; see loadObjFile). Faces keep their winding;
// polygons are split by scene/polygon_triangulation.h. Coordinates must be finite numbers within
// kMaxCoordinate, and faces need at least three vertices that exist (1-based, or negative: relative to
// the vertices read so far). Errors in the file are located file:line:col in it and name `ref`, where
// the job refers to it; errors about the file as a whole are located at `ref`. Meshes above
// max_triangles are refused. `faces`, when given, receives the faces as written.
Mesh loadObjMesh(const std::filesystem::path& file, const FileLoc& ref, std::uint64_t max_triangles,
                 ObjFaces* faces = nullptr);

// The same, from text already in memory; `name` is the file name in locations.
Mesh parseObjMesh(const std::string& text, const std::string& name, const FileLoc& ref,
                  std::uint64_t max_triangles, ObjFaces* faces = nullptr);

// An OBJ file with its material: `mtllib` files (relative to the OBJ file) are read for `newmtl`, `Kd`
// (the base colour) and `map_Kd` (an image texture, relative to the .mtl file, which must exist), other
// statements ignored; the `usemtl` material, if any, is `material`. One material per file: a second,
// different `usemtl` is an error (split the file into objects). Corner attributes: a face corner
// without `vt` reads (0, 0), one without `vn` takes its triangle's face normal when the file has normals;
// `vt`'s v is flipped to the image's t-down convention.
struct ObjFile {
    Mesh mesh;
    ObjFaces faces;
    std::optional<Material> material;
    std::vector<std::filesystem::path> material_files;  // the .mtl files read
};
ObjFile loadObjFile(const std::filesystem::path& file, const FileLoc& ref, std::uint64_t max_triangles);
ObjFile parseObjFile(const std::string& text, const std::string& name, const FileLoc& ref,
                     std::uint64_t max_triangles);

}  // namespace clipblur
