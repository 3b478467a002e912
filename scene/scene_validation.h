#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace clipblur {

inline constexpr double kMaxCoordinate = 1e8;

// Where the keyed parts of a scene were written, for errors found after the scene is built.
// Empty vectors (a scene built in code) give errors without a location.
struct SceneLocations {
    std::vector<FileLoc> camera_keys;
    std::vector<std::vector<FileLoc>> transform_keys;    // per object
    std::vector<std::vector<FileLoc>> deformation_keys;  // per object
};

struct SceneSummary {
    std::size_t objects = 0;
    std::uint64_t triangles = 0;
    std::uint64_t degenerate_triangles = 0;
};

// A triangle with a repeated index or (near-)zero area relative to its edge lengths.
bool isDegenerate(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
std::uint64_t countDegenerateTriangles(const Mesh& mesh);

// True when every undirected edge is used by exactly two triangles, once in each direction: a
// closed, consistently wound surface.
bool isClosedManifold(const Mesh& mesh);

// Checks what must hold for rendering and throws a scene error (with the best location known):
// no objects or no triangles, non-finite or absurd (|x| > 1e8) coordinates, triangle indices out
// of range, deformation keys whose vertex count differs from the mesh, keys not strictly
// increasing in time, a camera view that is zero or parallel to up, materials out of range.
// Returns warnings: degenerate triangles (kept, counted) and a camera inside a closed object.
std::vector<std::string> validateScene(const Scene& scene, const SceneLocations& locations = {});

SceneSummary summarizeScene(const Scene& scene);

}  // namespace clipblur
