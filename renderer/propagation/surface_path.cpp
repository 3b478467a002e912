#include "renderer/propagation/surface_path.h"

#include <algorithm>

#include "scene/exact_camera.h"
#include "scene/rotation.h"

namespace clipblur {

namespace {

// The key segment that governs time t, matching evalTransform / evalVertex / evalCamera: segment i
// holds keys[i].time <= t < keys[i+1].time. `moving` is false when t is outside the keys (held value).
struct Segment {
    std::size_t index = 0;
    double weight = 0.0;
    double rate = 0.0;  // d weight / dt
    bool moving = false;
};

template <typename Key>
Segment segmentAt(const std::vector<Key>& keys, double t) {
    if (keys.size() < 2 || t < keys.front().time) return {};
    if (t >= keys.back().time) return {keys.size() - 1, 0.0, 0.0, false};
    const auto next = std::upper_bound(keys.begin(), keys.end(), t,
                                       [](double time, const Key& k) { return time < k.time; });
    const std::size_t i = static_cast<std::size_t>(next - keys.begin()) - 1;
    const double span = keys[i + 1].time - keys[i].time;
    return {i, (t - keys[i].time) / span, 1.0 / span, true};
}

ObjectMotionState objectStateAt(const Object& object, double t) {
    ObjectMotionState state;
    if (object.motion) {
        state.exact = object.motion->pose(object.mesh.positions, t, ExactMotion::Rates::Compute);
        return state;
    }
    state.transform = evalTransform(object.transform, t);
    const Segment rigid = segmentAt(object.transform, t);
    if (rigid.moving) {
        const TransformKey& a = object.transform[rigid.index];
        const TransformKey& b = object.transform[rigid.index + 1];
        state.translate_rate = (b.translate - a.translate) * rigid.rate;
        state.scale_rate = (b.scale - a.scale) * rigid.rate;
        // slerp(qa, qb, w) = (qb qa^-1)^w qa: a constant-rate rotation about the world axis of qb qa^-1.
        // IntraframeRotation picks the shorter arc exactly as evalTransform does.
        const IntraframeRotation relative(glm::normalize(b.rotate) * glm::conjugate(glm::normalize(a.rotate)));
        state.angular_velocity = relative.angularVelocity() * rigid.rate;
    }
    const Segment deform = segmentAt(object.deformation, t);
    state.deform_key = deform.index;
    state.deform_weight = deform.weight;
    state.deform_rate = deform.moving ? deform.rate : 0.0;
    return state;
}

// World position of a surface point of an exactly moving object and, when `rate` is given, its time
// derivative: the convex combination of its triangle's posed vertices (the pose is affine per vertex).
glm::dvec3 exactPoint(const Object& object, const ExactPose& pose, const MeshPoint& point, glm::dvec3* rate) {
    const auto& tri = object.mesh.triangles[point.triangle];
    glm::dvec3 position(0.0);
    if (rate) *rate = glm::dvec3(0.0);
    for (int j = 0; j < 3; ++j) {
        position += point.b[j] * pose.vertex(tri[j]);
        if (rate) *rate += point.b[j] * pose.vertexRate(tri[j]);
    }
    return position;
}

// Object-space position of the surface point and, when `rate` is given, its time derivative.
glm::dvec3 objectSpacePoint(const Object& object, const ObjectMotionState& state, const MeshPoint& point,
                            glm::dvec3* rate) {
    const auto& tri = object.mesh.triangles[point.triangle];
    glm::dvec3 position(0.0);
    if (rate) *rate = glm::dvec3(0.0);
    if (object.deformation.empty()) {
        for (int j = 0; j < 3; ++j) position += point.b[j] * object.mesh.positions[tri[j]];
        return position;
    }
    const auto& k0 = object.deformation[state.deform_key].positions;
    if (state.deform_weight == 0.0 && state.deform_rate == 0.0) {
        for (int j = 0; j < 3; ++j) position += point.b[j] * k0[tri[j]];
        return position;
    }
    const auto& k1 = object.deformation[state.deform_key + 1].positions;
    for (int j = 0; j < 3; ++j) position += point.b[j] * glm::mix(k0[tri[j]], k1[tri[j]], state.deform_weight);
    if (rate) {
        for (int j = 0; j < 3; ++j) *rate += point.b[j] * (k1[tri[j]] - k0[tri[j]]);
        *rate *= state.deform_rate;
    }
    return position;
}

}  // namespace

MotionSnapshot::MotionSnapshot(const Scene& scene, const Projection& proj, double t, double near)
    : time(t), projection(proj), near_depth(near) {
    const auto& keys = scene.camera.keys;
    if (scene.camera.motion) {
        CameraRates rates;
        camera = scene.camera.motion->at(t, &rates);
        camera_velocity = rates.velocity;
        camera_angular_velocity = rates.angular_velocity;
    } else {
        camera = evalCamera(scene.camera, t);
        const Segment seg = segmentAt(keys, t);
        if (seg.moving) {
            const CameraKey& k0 = keys[seg.index];
            const CameraKey& k1 = keys[seg.index + 1];
            const CameraMotion motion(makeCameraFrame(k0.position, k0.view, k0.up),
                                      makeCameraFrame(k1.position, k1.view, k1.up));
            camera_velocity = motion.velocity() * seg.rate;
            camera_angular_velocity = motion.rotation().angularVelocity() * seg.rate;
        }
    }
    objects.reserve(scene.objects.size());
    for (const Object& object : scene.objects) objects.push_back(objectStateAt(object, t));
}

namespace {

// Shared by project and projectMotion; d is r - rc.
ProjectedPoint projectRelative(const MotionSnapshot& s, const glm::dvec3& world, const glm::dvec3& d) {
    ProjectedPoint out;
    out.world = world;
    out.depth = glm::dot(s.camera.e3, d);
    if (!(out.depth > s.near_depth)) {
        out.behind = true;
        return out;
    }
    out.inv_depth = 1.0 / out.depth;
    const glm::dvec2 p(glm::dot(s.camera.e1, d) * out.inv_depth, glm::dot(s.camera.e2, d) * out.inv_depth);
    out.raster = s.projection.toRaster(p);
    return out;
}

}  // namespace

ProjectedPoint project(const MotionSnapshot& snapshot, const Scene& scene, const MeshPoint& point) {
    const Object& object = scene.objects[point.object];
    const ObjectMotionState& state = snapshot.objects[point.object];
    if (state.exact) {
        const glm::dvec3 world = exactPoint(object, *state.exact, point, nullptr);
        return projectRelative(snapshot, world, world - snapshot.camera.position);
    }
    const glm::dvec3 local = objectSpacePoint(object, state, point, nullptr);
    // Affine transform of a convex combination = convex combination of transformed vertices.
    const glm::dvec3 world = state.transform.apply(local);
    return projectRelative(snapshot, world, world - snapshot.camera.position);
}

glm::dmat3 cameraTurn(const MotionSnapshot& to, const MotionSnapshot& from) {
    // Homogeneous raster = K (e1 . d, e2 . d, e3 . d): raster x = W/2 + k (e2 . d) / z, y = H/2 - k (e1 . d) / z.
    const Projection& p = from.projection;
    const double k = p.pixelsPerUnit();
    const glm::dmat3 K(glm::dvec3(0.0, -k, 0.0), glm::dvec3(k, 0.0, 0.0), glm::dvec3(0.5 * p.width, 0.5 * p.height, 1.0));
    return K * glm::transpose(to.camera.basis()) * from.camera.basis() * glm::inverse(K);
}

std::vector<glm::dmat3> cameraTurns(const Scene& scene, const Projection& projection, double middle,
                                    std::span<const double> times) {
    const MotionSnapshot from(scene, projection, middle);
    std::vector<glm::dmat3> turns;
    bool turning = false;
    for (const double t : times) {
        const MotionSnapshot to(scene, projection, t);
        turning = turning || to.camera.basis() != from.camera.basis();
        turns.push_back(cameraTurn(to, from));
    }
    if (!turning) turns.clear();
    return turns;
}

namespace {

// World position and rate of a surface point at the snapshot's time.
void worldMotion(const MotionSnapshot& snapshot, const Scene& scene, const MeshPoint& point, glm::dvec3& world,
                 glm::dvec3& world_rate) {
    const Object& object = scene.objects[point.object];
    const ObjectMotionState& state = snapshot.objects[point.object];
    if (state.exact) {
        world = exactPoint(object, *state.exact, point, &world_rate);
        return;
    }
    glm::dvec3 local_rate;
    const glm::dvec3 local = objectSpacePoint(object, state, point, &local_rate);
    const RigidTransform& xf = state.transform;
    const glm::dvec3 rotated = xf.rotate * (xf.scale * local);
    world = xf.translate + rotated;
    world_rate = state.translate_rate + glm::cross(state.angular_velocity, rotated) +
                 xf.rotate * (state.scale_rate * local + xf.scale * local_rate);
}

ProjectedMotion projectRelativeMotion(const MotionSnapshot& snapshot, const glm::dvec3& world, const glm::dvec3& d,
                                      const glm::dvec3& g) {
    ProjectedMotion out;
    out.point = projectRelative(snapshot, world, d);
    out.depth_rate = glm::dot(snapshot.camera.e3, g);
    if (out.point.behind) return out;
    const double z = out.point.depth;
    const double p1 = glm::dot(snapshot.camera.e1, d) / z;
    const double p2 = glm::dot(snapshot.camera.e2, d) / z;
    const double p1_rate = (glm::dot(snapshot.camera.e1, g) - p1 * out.depth_rate) / z;
    const double p2_rate = (glm::dot(snapshot.camera.e2, g) - p2 * out.depth_rate) / z;
    // toRaster: x = W/2 + k p2, y = H/2 - k p1.
    const double k = snapshot.projection.pixelsPerUnit();
    out.raster_velocity = {k * p2_rate, -k * p1_rate};
    return out;
}

}  // namespace

ProjectedMotion projectMotion(const MotionSnapshot& snapshot, const Scene& scene, const MeshPoint& point) {
    glm::dvec3 world, world_rate;
    worldMotion(snapshot, scene, point, world, world_rate);
    const glm::dvec3 d = world - snapshot.camera.position;
    const glm::dvec3 g = (world_rate - snapshot.camera_velocity) + glm::cross(d, snapshot.camera_angular_velocity);
    return projectRelativeMotion(snapshot, world, d, g);
}

CameraRelative cameraRelative(const MotionSnapshot& snapshot, const Scene& scene, const MeshPoint& point) {
    glm::dvec3 world, world_rate;
    worldMotion(snapshot, scene, point, world, world_rate);
    CameraRelative out;
    out.d = world - snapshot.camera.position;
    out.g = (world_rate - snapshot.camera_velocity) + glm::cross(out.d, snapshot.camera_angular_velocity);
    return out;
}

ProjectedMotion projectMotion(const MotionSnapshot& snapshot, const CameraRelative& relative) {
    return projectRelativeMotion(snapshot, relative.d + snapshot.camera.position, relative.d, relative.g);
}

}  // namespace clipblur
