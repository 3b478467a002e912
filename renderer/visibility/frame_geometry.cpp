#include "renderer/visibility/frame_geometry.h"

#include <algorithm>
#include <cmath>

#include "renderer/geometry/predicates.h"
#include "scene/object_motion.h"

namespace clipblur {

NearClipped clipToNearPlane(const CameraFrame& camera, double near, std::span<const glm::dvec3> world,
                            std::span<const glm::dvec3> bary) {
    const std::size_t n = world.size();
    NearClipped out;
    int& count = out.count;
    std::array<glm::dvec3, 4>& world_out = out.world;
    std::array<glm::dvec3, 4>& bary_out = out.bary;
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t j = (i + 1) % n;
        const double di = glm::dot(camera.e3, world[i] - camera.position) - near;
        const double dj = glm::dot(camera.e3, world[j] - camera.position) - near;
        if (di >= 0.0 && count < 4) {
            world_out[count] = world[i];
            bary_out[count++] = bary[i];
        }
        if ((di >= 0.0) != (dj >= 0.0) && count < 4) {
            const double s = di / (di - dj);
            world_out[count] = world[i] + s * (world[j] - world[i]);
            bary_out[count++] = bary[i] + s * (bary[j] - bary[i]);
        }
    }
    return out;
}

FrameGeometry::FrameGeometry(const FrameMotion& motion, const Projection& projection, double time,
                             const TileGrid& grid)
    : time_(time), projection_(projection), grid_(grid), camera_(motion.camera(time)) {
    const Scene& scene = motion.scene();
    std::vector<glm::dvec3> world;
    object_base_.reserve(scene.objects.size() + 1);
    mesh_offsets_.push_back(0);
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        object_base_.push_back(static_cast<std::uint32_t>(mesh_offsets_.size() - 1));
        motion.vertices(o, time, world);
        for (std::uint32_t t = 0; t < object.mesh.triangles.size(); ++t) {
            const auto& idx = object.mesh.triangles[t];
            addTriangle(o, t, {world[idx[0]], world[idx[1]], world[idx[2]]}, projection);
            mesh_offsets_.push_back(static_cast<std::uint32_t>(mesh_items_.size()));
        }
        mesh_triangles_ += static_cast<long long>(object.mesh.triangles.size());
    }
    object_base_.push_back(static_cast<std::uint32_t>(mesh_offsets_.size() - 1));

    // Bin by raster bounding box; counting pass then fill, so each tile's list is in index order.
    const int columns = grid.columns();
    const int rows = grid.rows();
    const double size = grid.tileSize();
    tile_offsets_.assign(static_cast<std::size_t>(grid.count()) + 1, 0);
    auto tileRange = [&](const ScreenTriangle& t, int& c0, int& c1, int& r0, int& r1) {
        const double x0 = std::min({t.raster[0].x, t.raster[1].x, t.raster[2].x});
        const double x1 = std::max({t.raster[0].x, t.raster[1].x, t.raster[2].x});
        const double y0 = std::min({t.raster[0].y, t.raster[1].y, t.raster[2].y});
        const double y1 = std::max({t.raster[0].y, t.raster[1].y, t.raster[2].y});
        c0 = static_cast<int>(std::clamp(std::floor((x0 - grid.x0()) / size), 0.0, double(columns)));
        c1 = static_cast<int>(std::clamp(std::floor((x1 - grid.x0()) / size), -1.0, double(columns - 1)));
        r0 = static_cast<int>(std::clamp(std::floor((y0 - grid.y0()) / size), 0.0, double(rows)));
        r1 = static_cast<int>(std::clamp(std::floor((y1 - grid.y0()) / size), -1.0, double(rows - 1)));
    };
    for (const ScreenTriangle& t : triangles_) {
        int c0, c1, r0, r1;
        tileRange(t, c0, c1, r0, r1);
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c) ++tile_offsets_[static_cast<std::size_t>(r * columns + c) + 1];
    }
    for (std::size_t i = 1; i < tile_offsets_.size(); ++i) tile_offsets_[i] += tile_offsets_[i - 1];
    tile_items_.resize(tile_offsets_.back());
    std::vector<std::uint32_t> cursor(tile_offsets_.begin(), tile_offsets_.end() - 1);
    for (std::uint32_t i = 0; i < triangles_.size(); ++i) {
        int c0, c1, r0, r1;
        tileRange(triangles_[i], c0, c1, r0, r1);
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c) tile_items_[cursor[static_cast<std::size_t>(r * columns + c)]++] = i;
    }
}

namespace {

const std::array<glm::dvec3, 3> kCorners{glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)};

}  // namespace

void FrameGeometry::addTriangle(std::uint32_t object, std::uint32_t triangle, const std::array<glm::dvec3, 3>& world,
                                const Projection& projection) {
    bool all_front = true;
    for (const auto& p : world) all_front = all_front && glm::dot(camera_.e3, p - camera_.position) >= kNearDepth;
    if (all_front) {
        emit(object, triangle, world, kCorners, projection);
        return;
    }
    const NearClipped c = clipToNearPlane(camera_, kNearDepth, world, kCorners);
    const int n = c.count;
    const auto& w = c.world;
    const auto& b = c.bary;
    if (n == 0) return;
    ++near_clipped_;
    emit(object, triangle, {w[0], w[1], w[2]}, {b[0], b[1], b[2]}, projection);
    if (n == 4) emit(object, triangle, {w[0], w[2], w[3]}, {b[0], b[2], b[3]}, projection);
}

void FrameGeometry::emit(std::uint32_t object, std::uint32_t triangle, const std::array<glm::dvec3, 3>& world,
                         const std::array<glm::dvec3, 3>& bary, const Projection& projection) {
    ScreenTriangle s;
    for (int i = 0; i < 3; ++i) {
        const ImagePoint ip = projectToImagePlane(camera_, world[i]);
        s.raster[i] = projection.toRaster(ip.p);
        s.inv_depth[i] = 1.0 / ip.depth;
    }
    if (!validScreenTriangle(s)) return;  // edge-on or degenerate: covers no area
    s.source = static_cast<std::uint32_t>(triangles_.size());
    mesh_items_.push_back(s.source);
    triangles_.push_back(s);
    mesh_triangle_.push_back({object, triangle});
    if (bary != kCorners) {
        clipped_.push_back(s.source);
        clipped_bary_.push_back(bary);
    }
    // Inradius = area / half-perimeter = |cross| / perimeter.
    const double perimeter = glm::distance(s.raster[0], s.raster[1]) + glm::distance(s.raster[1], s.raster[2]) +
                             glm::distance(s.raster[2], s.raster[0]);
    inner_diameter_.push_back(2.0 * std::abs(orient2d(s.raster[0], s.raster[1], s.raster[2])) / perimeter);
}

SourceTriangle FrameGeometry::source(std::uint32_t screen_triangle) const {
    const auto& [object, triangle] = mesh_triangle_[screen_triangle];
    const auto c = std::lower_bound(clipped_.begin(), clipped_.end(), screen_triangle);
    if (c == clipped_.end() || *c != screen_triangle) return {object, triangle, kCorners};
    return {object, triangle, clipped_bary_[static_cast<std::size_t>(c - clipped_.begin())]};
}

std::span<const std::uint32_t> FrameGeometry::tileTriangles(int tile) const {
    const auto t = static_cast<std::size_t>(tile);
    return {tile_items_.data() + tile_offsets_[t], tile_items_.data() + tile_offsets_[t + 1]};
}

std::span<const std::uint32_t> FrameGeometry::ofMeshTriangle(std::uint32_t object, std::uint32_t triangle) const {
    const std::size_t g = object_base_[object] + triangle;
    return {mesh_items_.data() + mesh_offsets_[g], mesh_items_.data() + mesh_offsets_[g + 1]};
}

}  // namespace clipblur
