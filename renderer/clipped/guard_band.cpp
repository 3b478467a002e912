#include "renderer/clipped/guard_band.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "renderer/clipped/motion_plan.h"
#include "renderer/parallel_time.h"
#include "scene/object_motion.h"

namespace clipblur {

namespace {

constexpr int kTimeSamples = 9;

struct Raster {
    glm::dvec2 p{0.0};
    bool valid = false;
};

Raster toRaster(const CameraFrame& camera, const Projection& projection, const glm::dvec3& world) {
    const ImagePoint ip = projectToImagePlane(camera, world);
    if (!(ip.depth > 1e-6)) return {};
    return {projection.toRaster(ip.p), true};
}

// Largest over times of min(distance to the position at open, at close), for samples near the image.
double bandOf(const std::array<Raster, kTimeSamples>& path, const Projection& projection) {
    const Raster& a = path.front();
    const Raster& b = path.back();
    const double slack = 0.25 * std::max(projection.width, projection.height);
    double band = 0.0;
    for (const Raster& r : path) {
        if (!r.valid) continue;
        const bool near_image = r.p.x > -slack && r.p.y > -slack && r.p.x < projection.width + slack &&
                                r.p.y < projection.height + slack;
        if (!near_image) continue;
        double d = std::numeric_limits<double>::infinity();
        if (a.valid) d = std::min(d, glm::length(r.p - a.p));
        if (b.valid) d = std::min(d, glm::length(r.p - b.p));
        if (std::isfinite(d)) band = std::max(band, d);
    }
    return band;
}

}  // namespace

int guardBandPixels(const FrameMotion& motion, const Projection& projection, const MotionWindow& window, int cap) {
    const Scene& scene = motion.scene();
    const double t0 = window.t0, t1 = window.t1;
    const bool still_camera = window.camera_still;
    std::array<double, kTimeSamples> times{};
    std::array<CameraFrame, kTimeSamples> cameras{};
    for (int k = 0; k < kTimeSamples; ++k) {
        times[k] = t0 + (t1 - t0) * k / (kTimeSamples - 1);
        cameras[k] = motion.camera(times[k]);
    }
    double band = 0.0;

    // Camera rotation: directions seen at the image border at time t, where they were at open and close.
    if (!still_camera) {
        const double w = projection.width, h = projection.height;
        for (const glm::dvec2 q : {glm::dvec2(0, 0), glm::dvec2(w, 0), glm::dvec2(0, h), glm::dvec2(w, h),
                                   glm::dvec2(w / 2, 0), glm::dvec2(w / 2, h), glm::dvec2(0, h / 2), glm::dvec2(w, h / 2)}) {
            for (int k = 0; k < kTimeSamples; ++k) {
                const glm::dvec2 p = projection.toImagePlane(q);
                const glm::dvec3 dir = cameras[k].e3 + p.x * cameras[k].e1 + p.y * cameras[k].e2;
                std::array<Raster, kTimeSamples> path{};
                path[0] = toRaster({glm::dvec3(0.0), cameras[0].e1, cameras[0].e2, cameras[0].e3}, projection, dir);
                path[kTimeSamples - 1] = toRaster({glm::dvec3(0.0), cameras.back().e1, cameras.back().e2, cameras.back().e3},
                                                  projection, dir);
                path[k] = {q, true};
                band = std::max(band, bandOf(path, projection));
            }
        }
    }

    // Points on the meshes: vertices, triangle centroids and edge midpoints. Objects in parallel: a
    // maximum is the same in any order (the particles' 500 objects were a serial tenth of a second per
    // segment).
    const auto objectBand = [&](std::size_t o) {
        const Object& object = scene.objects[o];
        if (window.stillInImage(o)) return 0.0;
        std::array<std::vector<glm::dvec3>, kTimeSamples> world;
        for (int k = 0; k < kTimeSamples; ++k) motion.vertices(o, times[k], world[k]);
        double most = 0.0;
        const auto track = [&](auto&& point) {
            std::array<Raster, kTimeSamples> path{};
            for (int k = 0; k < kTimeSamples; ++k) path[k] = toRaster(cameras[k], projection, point(world[k]));
            most = std::max(most, bandOf(path, projection));
        };
        for (std::size_t v = 0; v < object.mesh.positions.size(); ++v)
            track([&](const std::vector<glm::dvec3>& w) { return w[v]; });
        for (const auto& t : object.mesh.triangles) {
            track([&](const std::vector<glm::dvec3>& w) { return (w[t[0]] + w[t[1]] + w[t[2]]) / 3.0; });
            for (int e = 0; e < 3; ++e)
                track([&](const std::vector<glm::dvec3>& w) { return 0.5 * (w[t[e]] + w[t[(e + 1) % 3]]); });
        }
        return most;
    };
    band = std::max(band, parallelReduce(
                              tbb::blocked_range<std::size_t>(0, scene.objects.size()), 0.0,
                              [&](const tbb::blocked_range<std::size_t>& range, double most) {
                                  for (std::size_t o = range.begin(); o != range.end(); ++o) most = std::max(most, objectBand(o));
                                  return most;
                              },
                              [](double a, double b) { return std::max(a, b); }));
    return static_cast<int>(std::min<double>(cap, std::ceil(band + 1.0)));
}

}  // namespace clipblur
