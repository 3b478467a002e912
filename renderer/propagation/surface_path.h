#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/camera.h"
#include "scene/exact_motion.h"
#include "scene/object_motion.h"
#include "scene/scene.h"

namespace clipblur {

// A point fixed on a source mesh triangle. Fragment vertices produced by clipping at shutter open or
// close are all of this form; b is a convex combination (sums to 1).
struct MeshPoint {
    std::uint32_t object = 0;
    std::uint32_t triangle = 0;
    glm::dvec3 b{1.0 / 3.0};
};

// Camera depths at or below this (world units) count as on or behind the camera plane.
inline constexpr double kDefaultNearDepth = 1e-6;

// The motion state of one object at one time: where its keys put it and how fast it moves.
// Rates are per unit of absolute time (frames) and are right derivatives at key times; outside the
// keys the object is held, so its rates are zero.
struct ObjectMotionState {
    RigidTransform transform;
    glm::dvec3 translate_rate{0.0};
    glm::dvec3 scale_rate{0.0};
    glm::dvec3 angular_velocity{0.0};  // world frame: d/dt (R v) = angular_velocity x (R v)
    std::size_t deform_key = 0;        // object-space positions lerp(keys[k], keys[k+1], weight)
    double deform_weight = 0.0;
    double deform_rate = 0.0;          // d weight / dt
    std::optional<ExactPose> exact;    // an exact motion's pose and rates; then the fields above are unused
};

// Everything about the scene's motion at one time that projecting a surface point needs, computed once
// per subframe time so that projecting each fragment vertex is a few dot products.
struct MotionSnapshot {
    MotionSnapshot(const Scene& scene, const Projection& projection, double time,
                   double near_depth = kDefaultNearDepth);

    double time;
    Projection projection;
    double near_depth;
    CameraFrame camera;
    glm::dvec3 camera_velocity{0.0};          // d rc / dt
    glm::dvec3 camera_angular_velocity{0.0};  // d e_i / dt = camera_angular_velocity x e_i
    std::vector<ObjectMotionState> objects;
};

// A surface point seen by the camera at the snapshot's time. When `behind` is set (depth <= near) the
// raster position is meaningless: the point is crossing or behind the camera plane. Fragments with such
// a vertex must be clipped in 3D against the near plane by the caller (or dropped from that subframe);
// propagation never silently projects through the camera.
struct ProjectedPoint {
    glm::dvec2 raster{0.0};  // x right, y down, pixel centres at +0.5
    double depth = 0.0;      // n . (r - rc)
    double inv_depth = 0.0;  // 1 / depth, 0 when behind
    bool behind = false;
    glm::dvec3 world{0.0};
};

// A projected point and its exact time derivatives (analytic, not finite differences).
struct ProjectedMotion {
    ProjectedPoint point;
    glm::dvec2 raster_velocity{0.0};  // d raster / dt in pixels per frame, zero when behind
    double depth_rate = 0.0;          // d depth / dt
};

// Exact position: the propagated 3D surface point projected by the camera at the snapshot's time.
ProjectedPoint project(const MotionSnapshot& snapshot, const Scene& scene, const MeshPoint& point);

// The camera's turn between two snapshots as a map of homogeneous raster coordinates (raster x depth,
// depth): a point at a given position relative to the camera centre, seen with `from`'s orientation at h,
// is seen with `to`'s at cameraTurn(to, from) h. One homography for every point; the identity when the
// orientation is the same.
glm::dmat3 cameraTurn(const MotionSnapshot& to, const MotionSnapshot& from);

// The camera's turns from time `middle` to each of `times` (cameraTurn), or none when its orientation is
// the same at all of them.
std::vector<glm::dmat3> cameraTurns(const Scene& scene, const Projection& projection, double middle,
                                    std::span<const double> times);

// Position plus analytic velocity. With d = r - rc, e_i' = W x e_i and g = d' + d x W, the image-plane
// coordinates p_i = e_i.d / e3.d have p_i' = (e_i.g - p_i e3.g) / (e3.d).
ProjectedMotion projectMotion(const MotionSnapshot& snapshot, const Scene& scene, const MeshPoint& point);

// projectMotion's d and g for a surface point. Both are linear in its barycentrics (its world position
// and rate are), so a mesh triangle's corners give them for every point of it.
struct CameraRelative {
    glm::dvec3 d{0.0}, g{0.0};
};
CameraRelative cameraRelative(const MotionSnapshot& snapshot, const Scene& scene, const MeshPoint& point);
// The point with those d and g, as projectMotion projects it (world = d + rc).
ProjectedMotion projectMotion(const MotionSnapshot& snapshot, const CameraRelative& relative);

}  // namespace clipblur
