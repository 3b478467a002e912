#include "renderer/clipped/still_backdrop.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/clipped/motion_plan.h"
#include "renderer/visibility/embree_device.h"
#include "scene/object_motion.h"

namespace clipblur {

namespace {

// The farthest depth any point of a moving object reaches in [t0, t1] under the still camera `frame`: its
// origin's depth (linear between transform keys, so extreme at t0, t1 or a key) plus the largest distance
// of a vertex from the origin (scale and deformation are linear between keys too, so bounded at them).
double farthestDepth(const FrameMotion& motion, std::size_t o, const CameraFrame& frame) {
    const Object& object = motion.scene().objects[o];
    // An exact glTF motion has no bound read off keys: it could reach anywhere, so nothing lies behind it.
    if (object.motion) return std::numeric_limits<double>::infinity();
    const double t0 = motion.t0(), t1 = motion.t1();
    std::vector<double> times{t0, t1};
    double scale = 0.0;
    for (const TransformKey& k : object.transform) {
        if (k.time > t0 && k.time < t1) times.push_back(k.time);
        scale = std::max({scale, std::abs(k.scale.x), std::abs(k.scale.y), std::abs(k.scale.z)});
    }
    if (object.transform.empty()) scale = 1.0;
    double radius = 0.0;
    for (const glm::dvec3& p : object.mesh.positions) radius = std::max(radius, glm::length(p));
    for (const DeformationKey& k : object.deformation)
        for (const glm::dvec3& p : k.positions) radius = std::max(radius, glm::length(p));
    double far = -std::numeric_limits<double>::infinity();
    for (double t : times)
        far = std::max(far, glm::dot(frame.e3, motion.transform(o, t).translate - frame.position));
    return far + scale * radius;
}

}  // namespace

Backdrop findBackdrop(const RenderJob& job, const FrameMotion& motion) {
    const Scene& scene = job.scene;
    if (!job.render.maySweep() || job.render.shadows ||
        job.render.method != Method::Clipped || !motion.shutter().camera_still)
        return {};
    Backdrop backdrop;
    backdrop.objects.resize(scene.objects.size());
    bool still = false, moving = false;
    const CameraFrame frame = motion.camera(motion.t0());
    double moving_far = -std::numeric_limits<double>::infinity(), still_near = std::numeric_limits<double>::infinity();
    std::vector<glm::dvec3> world;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        if (object.mesh.triangles.empty()) continue;
        backdrop.objects[o] = motion.shutter().objectStill(o);
        if (backdrop.objects[o]) {
            still = true;
            motion.vertices(o, motion.t0(), world);
            for (const glm::dvec3& p : world) still_near = std::min(still_near, glm::dot(frame.e3, p - frame.position));
        } else {
            moving = true;
            moving_far = std::max(moving_far, farthestDepth(motion, o, frame));
        }
    }
    if (!still || !moving) return {};
    backdrop.behind_everything = moving_far < still_near;
    return backdrop;
}

PixelSums renderBackdrop(const RenderJob& job, const FrameSetup& frame, const Backdrop& backdrop, double time,
                         FrameFragmentStats& stats) {
    Scene still = job.scene;
    still.objects.clear();
    std::vector<int> original;  // per object of `still`, its index in the job's scene
    for (std::size_t o = 0; o < job.scene.objects.size(); ++o) {
        if (!backdrop.objects[o]) continue;
        still.objects.push_back(job.scene.objects[o]);
        original.push_back(static_cast<int>(o));
    }
    const FrameMotion motion(still, time, time);
    const FrameBuild build(
        motion, {.tile_size = frame.grid.tileSize(), .fragment_shading = job.render.fragment_shading}, frame.callbacks);
    const FrameSetup& setup = build.setup();
    PixelSums sums;
    sums.resize(static_cast<std::size_t>(still.film.width) * still.film.height, job.output.cryptomatte.enabled);
    buildFrameFragments(
        setup, {.time = time, .rays_per_side = job.render.visibility_rays, .keep_triangles = false, .audit = job.render.audit},
        &sums, stats);
    // The mapping keeps object order, so each pixel's shares stay sorted.
    for (ObjectShares& shares : sums.objects)
        for (ObjectShare& s : shares) s.object = original[static_cast<std::size_t>(s.object)];
    return sums;
}

}  // namespace clipblur
