#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/fragments/screen_triangle.h"
#include "renderer/frame_motion.h"
#include "renderer/tiles.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace clipblur {

// Camera depth below which geometry counts as crossing the camera plane; triangles are clipped in 3D
// there before projection, so nothing behind the camera is drawn. In scene units: small against any
// sensible scene, large enough that raster coordinates of clipped vertices stay far from overflow.
inline constexpr double kNearDepth = 1e-4;

// Where a screen triangle comes from: a mesh triangle, or the part of one in front of the near plane.
struct SourceTriangle {
    std::uint32_t object = 0;
    std::uint32_t triangle = 0;
    std::array<glm::dvec3, 3> bary{};  // mesh-triangle barycentrics of the screen triangle's vertices
};

// The whole scene at one instant, projected: every triangle in front of the camera as a raster-space
// ScreenTriangle (source = index into sources), binned to the tiles its bounding box overlaps. This is
// the exhaustive candidate set; Embree's rays narrow it per tile (renderer/visibility/candidates.h).
class FrameGeometry {
public:
    FrameGeometry(const FrameMotion& motion, const Projection& projection, double time, const TileGrid& grid);

    double time() const { return time_; }
    const Projection& projection() const { return projection_; }
    PixelBounds tile(int index) const { return grid_.tile(index); }
    const CameraFrame& camera() const { return camera_; }
    std::span<const ScreenTriangle> triangles() const { return triangles_; }
    SourceTriangle source(std::uint32_t screen_triangle) const;
    // Screen triangles of the tile, in increasing index order.
    std::span<const std::uint32_t> tileTriangles(int tile) const;
    // Screen triangles made from mesh triangle `triangle` of `object` (0, 1 or 2 after near clipping).
    std::span<const std::uint32_t> ofMeshTriangle(std::uint32_t object, std::uint32_t triangle) const;
    // Diameter of the largest disk inside the raster triangle (twice its inradius): a triangle narrower
    // than the diagonal of the ray grid's cell can fall between rays, at any angle.
    double innerDiameter(std::uint32_t screen_triangle) const { return inner_diameter_[screen_triangle]; }

    long long meshTriangles() const { return mesh_triangles_; }
    long long clippedByNearPlane() const { return near_clipped_; }

private:
    void addTriangle(std::uint32_t object, std::uint32_t triangle, const std::array<glm::dvec3, 3>& world,
                     const Projection& projection);
    void emit(std::uint32_t object, std::uint32_t triangle, const std::array<glm::dvec3, 3>& world,
              const std::array<glm::dvec3, 3>& bary, const Projection& projection);

    double time_;
    Projection projection_;
    TileGrid grid_;
    CameraFrame camera_;
    std::vector<ScreenTriangle> triangles_;
    // Per screen triangle its mesh triangle (object, triangle); the barycentrics only of the near-clipped
    // parts (screen index ascending), the rest being the whole triangle: 72 bytes a triangle saved.
    std::vector<std::array<std::uint32_t, 2>> mesh_triangle_;
    std::vector<std::uint32_t> clipped_;
    std::vector<std::array<glm::dvec3, 3>> clipped_bary_;
    std::vector<double> inner_diameter_;
    std::vector<std::uint32_t> object_base_;        // first global mesh-triangle id of each object
    std::vector<std::uint32_t> mesh_offsets_;       // CSR: global mesh triangle -> screen triangles
    std::vector<std::uint32_t> mesh_items_;
    std::vector<std::uint32_t> tile_offsets_;       // CSR: tile -> screen triangles
    std::vector<std::uint32_t> tile_items_;
    long long mesh_triangles_ = 0;
    long long near_clipped_ = 0;
};

// A triangle's part at camera depth >= near: `count` vertices (0, 3 or 4), their world positions and
// per-vertex attributes.
struct NearClipped {
    int count = 0;
    std::array<glm::dvec3, 4> world{};
    std::array<glm::dvec3, 4> bary{};
};

// Clips the polygon `world` (with per-vertex attributes `bary`) to camera depth >= near, in 3D, where
// both interpolate linearly.
NearClipped clipToNearPlane(const CameraFrame& camera, double near, std::span<const glm::dvec3> world,
                            std::span<const glm::dvec3> bary);

}  // namespace clipblur
