#include "renderer/frame_motion.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

#include "scene/exact_motion.h"

namespace clipblur {

namespace {

double angleBetween(const glm::dquat& a, const glm::dquat& b) {
    const double c = std::min(1.0, std::abs(glm::dot(glm::normalize(a), glm::normalize(b))));
    return 2.0 * std::acos(c);
}

// Whether same(camera at a, camera at t) holds for t = b and every key time inside (a, b). Between keys
// the camera moves linearly and turns at a constant rate by less than pi, so for a comparison of position
// or orientation these times decide every t in [a, b].
template <class Same>
bool cameraKeeps(const Camera& camera, const CameraPath& path, double a, double b, Same&& same) {
    const CameraFrame open = path.at(a);
    if (!same(open, path.at(b))) return false;
    for (const CameraKey& key : camera.keys)
        if (key.time > a && key.time < b && !same(open, path.at(key.time))) return false;
    return true;
}

// The rotation of a general (possibly sheared) matrix, its columns made orthonormal from the first: what
// a turn count needs, not a decomposition.
glm::dquat orientationOf(const glm::dmat4& m) {
    const glm::dvec3 x = glm::normalize(glm::dvec3(m[0]));
    const glm::dvec3 c1(m[1]);
    const glm::dvec3 y = glm::normalize(c1 - glm::dot(c1, x) * x);
    return glm::quat_cast(glm::dmat3(x, y, glm::cross(x, y)));
}

}  // namespace

bool MotionWindow::anyObjectMoves() const {
    return std::any_of(object_still.begin(), object_still.end(), [](char still) { return !still; });
}

FrameMotion::FrameMotion(const Scene& scene, double t0, double t1)
    : scene_(scene), camera_(scene.camera), shutter_(windowOf(t0, t1, nullptr)) {}

MotionWindow FrameMotion::window(double a, double b) const { return windowOf(a, b, &shutter_); }

MotionWindow FrameMotion::windowOf(double a, double b, const MotionWindow* outer) const {
    MotionWindow w;
    w.t0 = a;
    w.t1 = b;
    // e2 = e3 x e1, so position, e1 and e3 decide the whole frame.
    const auto same_pose = [](const CameraFrame& p, const CameraFrame& q) {
        return p.position == q.position && p.e1 == q.e1 && p.e3 == q.e3;
    };
    const auto same_eye = [](const CameraFrame& p, const CameraFrame& q) { return p.position == q.position; };
    w.camera_still = (outer && outer->camera_still) || cameraKeeps(scene_.camera, camera_, a, b, same_pose);
    w.eye_still = w.camera_still || (outer && outer->eye_still) || cameraKeeps(scene_.camera, camera_, a, b, same_eye);
    w.object_still.resize(scene_.objects.size());
    for (std::size_t o = 0; o < scene_.objects.size(); ++o)
        w.object_still[o] = (outer && outer->object_still[o]) || isStatic(scene_.objects[o], a, b);
    return w;
}

RigidTransform FrameMotion::transform(std::size_t object, double t) const {
    return evalTransform(scene_.objects[object].transform, t);
}

void FrameMotion::vertices(std::size_t object, double t, std::vector<glm::dvec3>& out) const {
    evalVertices(scene_.objects[object], t, out);
}

std::vector<std::uint32_t> FrameMotion::groups(const MotionWindow& window) const {
    return motionGroups(scene_, window.t0, window.t1);
}

double FrameMotion::largestTurn() const {
    // Slerp and the camera's SO(3) interpolation turn at a constant rate within a key interval, and keys
    // turn by less than pi each; 256 samples resolve any shutter with fewer than 128 keys inside it.
    constexpr int kSamples = 256;
    const double t0 = shutter_.t0, t1 = shutter_.t1;
    const auto turn = [&](auto orientation) {
        double total = 0.0;
        glm::dquat previous = orientation(t0);
        for (int i = 1; i <= kSamples; ++i) {
            const glm::dquat q = orientation(t0 + (t1 - t0) * i / kSamples);
            total += angleBetween(previous, q);
            previous = q;
        }
        return total;
    };
    double largest = turn([&](double t) { return glm::quat_cast(camera(t).basis()); });
    for (std::size_t o = 0; o < scene_.objects.size(); ++o) {
        const Object& object = scene_.objects[o];
        if (object.motion && !object.motion->skinned()) {
            largest = std::max(largest, turn([&](double t) { return orientationOf(worldMatrix(object, t)); }));
            continue;
        }
        if (object.transform.size() < 2) continue;
        largest = std::max(largest, turn([&](double t) { return transform(o, t).rotate; }));
    }
    return largest;
}

}  // namespace clipblur
