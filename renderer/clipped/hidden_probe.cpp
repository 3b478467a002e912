#include "renderer/clipped/hidden_probe.h"

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "renderer/geometry/raster_bounds.h"
#include "renderer/parallel_time.h"
#include "renderer/propagation/surface_path.h"
#include "scene/camera.h"

namespace clipblur {

namespace {

// Whether the surface point is visible at the snapshot's time: in front of the camera, and the nearest
// surface along the ray from the eye to it is the point's own triangle or no nearer than the tolerance.
bool heldAt(const MotionSnapshot& end, const Scene& scene, const EmbreeScene& embree, const MeshPoint& point) {
    const ProjectedPoint q = project(end, scene, point);
    if (q.behind) return false;
    // Unnormalised, so the point itself lies at ray distance 1.
    const EmbreeHit hit = embree.intersect(end.camera.position, q.world - end.camera.position, end.time);
    if (!hit.hit) return true;  // Embree's surface passes a hair behind the exact point
    if (hit.object == static_cast<int>(point.object) && hit.triangle == point.triangle) return true;
    return hit.distance >= 1.0 - kHeldDepthTolerance;
}

}  // namespace

HiddenProbe probeHiddenAtBothEnds(const FrameSetup& frame, double a, double b, double at, int offset) {
    const Scene& scene = frame.scene();
    const EmbreeScene& embree = frame.embree;
    const Projection& projection = frame.projection;
    const MotionSnapshot open(scene, projection, a), close(scene, projection, b);
    const CameraFrame camera = frame.motion.camera(at);
    constexpr std::array<int, 4> kOffsetX{0, 1, 1, 0}, kOffsetY{0, 1, 0, 1};
    const int ox = kOffsetX[static_cast<std::size_t>(offset & 3)], oy = kOffsetY[static_cast<std::size_t>(offset & 3)];
    const int columns = (scene.film.width - ox + kProbeStride - 1) / kProbeStride;
    const int rows = (scene.film.height - oy + kProbeStride - 1) / kProbeStride;
    std::vector<HiddenProbe> per_row(static_cast<std::size_t>(std::max(rows, 0)));
    parallelFor(0, rows, [&](int r) {
        HiddenProbe& row = per_row[static_cast<std::size_t>(r)];
        const int y = r * kProbeStride + oy;
        for (int c = 0; c < columns; ++c) {
            const int x = c * kProbeStride + ox;
            const glm::dvec2 p = projection.toImagePlane(glm::dvec2(x + 0.5, y + 0.5));
            const EmbreeHit hit = embree.intersect(camera.position, camera.e3 + p.x * camera.e1 + p.y * camera.e2, at);
            if (!hit.hit) continue;
            ++row.samples;
            const MeshPoint point{static_cast<std::uint32_t>(hit.object), hit.triangle,
                                  glm::dvec3(1.0 - hit.u - hit.v, hit.u, hit.v)};
            if (heldAt(open, scene, embree, point) || heldAt(close, scene, embree, point)) continue;
            ++row.hidden;
            row.pixels.emplace_back(x, y);
        }
    });
    HiddenProbe total;
    for (const HiddenProbe& row : per_row) {
        total.samples += row.samples;
        total.hidden += row.hidden;
        total.pixels.insert(total.pixels.end(), row.pixels.begin(), row.pixels.end());
    }
    return total;
}

bool visibilityCanChange(const MotionWindow& window) { return !window.eye_still || window.anyObjectMoves(); }

TileSet hiddenTiles(const FrameSetup& frame, const ShutterSegment& segment, const std::function<int()>& reach,
                    HiddenProbe& total) {
    // The middle first: two objects crossing over one spot uncover it there.
    constexpr std::array<double, 3> kAt{0.5, 0.25, 0.75};
    const double a = segment.begin, b = segment.end;
    std::vector<glm::ivec2> hidden;
    for (std::size_t k = 0; k < kAt.size(); ++k) {
        const HiddenProbe probe =
            probeHiddenAtBothEnds(frame, a, b, a + (b - a) * kAt[k], static_cast<int>(k));
        total.samples += probe.samples;
        total.hidden += probe.hidden;
        hidden.insert(hidden.end(), probe.pixels.begin(), probe.pixels.end());
    }
    TileSet where = TileSet::none();
    if (hidden.empty()) return where;
    const int r = reach() + kProbeStride;
    for (const glm::ivec2& p : hidden)
        where.addOverlapping(frame.grid, PixelBounds::corners(p.x - r, p.y - r, p.x + r + 1, p.y + r + 1));
    return where;
}

TileSet turningObjectTiles(const FrameSetup& frame, const ShutterSegment& segment, const std::function<int()>& reach) {
    constexpr int kTimes = 9;
    const Scene& scene = frame.scene();
    const FrameMotion& motion = frame.motion;
    const double limit = kAutoSegmentTurnDegrees * std::numbers::pi / 180.0;
    TileSet where = TileSet::none();
    std::vector<glm::dvec3> world;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        if (!(motion.objectTurn(o, segment.begin, segment.end) > limit)) continue;
        RasterBounds box;
        for (int k = 0; k < kTimes; ++k) {
            const double t = segment.begin + (segment.end - segment.begin) * k / (kTimes - 1);
            const CameraFrame camera = motion.camera(t);
            motion.vertices(o, t, world);
            for (const glm::dvec3& v : world) {
                const ImagePoint ip = projectToImagePlane(camera, v);
                if (!(ip.depth > kDefaultNearDepth)) return TileSet();
                box.expand(frame.projection.toRaster(ip.p));
            }
        }
        if (box.empty()) continue;
        const int band = reach();
        // Clamped to the film grown by the band, so a box far beyond it is never cast to int.
        const glm::dvec2 lo = glm::max(box.lo - double(band), glm::dvec2(-band - 1.0));
        const glm::dvec2 hi = glm::min(box.hi + double(band), glm::dvec2(scene.film.width + band + 1.0, scene.film.height + band + 1.0));
        if (!(lo.x < hi.x && lo.y < hi.y)) continue;
        where.addOverlapping(frame.grid, PixelBounds::corners(int(std::floor(lo.x)), int(std::floor(lo.y)), int(std::ceil(hi.x)), int(std::ceil(hi.y))));
    }
    return where;
}

}  // namespace clipblur
