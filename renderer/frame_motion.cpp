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

// The turn of an exact camera over [t0, t1], summed along its motion: between two key times every
// track is one polynomial or slerp arc, smooth and turning by less than pi, so each such piece is cut
// into kPieceSamples chords: exact for a turn about a fixed axis, an undercount of relative order
// kPieceSamples^-2 for a curved one.
double exactCameraTurn(const ExactCamera& camera, double t0, double t1) {
    constexpr int kPieceSamples = 32;
    std::vector<double> times{t0};
    for (const double k : camera.keyTimes())
        if (k > t0 && k < t1) times.push_back(k);
    times.push_back(t1);
    const auto orientation = [&](double t) { return glm::quat_cast(camera.at(t).basis()); };
    double total = 0.0;
    glm::dquat previous = orientation(t0);
    for (std::size_t i = 0; i + 1 < times.size(); ++i)
        for (int j = 1; j <= kPieceSamples; ++j) {
            const double t = j == kPieceSamples ? times[i + 1] : times[i] + (times[i + 1] - times[i]) * j / kPieceSamples;
            const glm::dquat q = orientation(t);
            total += angleBetween(previous, q);
            previous = q;
        }
    return total;
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
    if (const ExactCamera* exact = camera_.exact()) {
        // Judged from the tracks: between key times the exact camera does not move at a constant rate.
        w.camera_still = (outer && outer->camera_still) || exact->constantOver(a, b);
        w.eye_still = w.camera_still || (outer && outer->eye_still) || exact->eyeConstantOver(a, b);
    } else {
        w.camera_still = (outer && outer->camera_still) || cameraKeeps(scene_.camera, camera_, a, b, same_pose);
        w.eye_still = w.camera_still || (outer && outer->eye_still) || cameraKeeps(scene_.camera, camera_, a, b, same_eye);
    }
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

namespace {

// The angle an orientation turns through over [t0, t1], summed over chords. Slerp and the camera's SO(3)
// interpolation turn at a constant rate within a key interval, and keys turn by less than pi each; 256
// samples resolve any window with fewer than 128 keys inside it.
template <class Orientation>
double turnOf(Orientation orientation, double t0, double t1) {
    constexpr int kSamples = 256;
    double total = 0.0;
    glm::dquat previous = orientation(t0);
    for (int i = 1; i <= kSamples; ++i) {
        const glm::dquat q = orientation(t0 + (t1 - t0) * i / kSamples);
        total += angleBetween(previous, q);
        previous = q;
    }
    return total;
}

}  // namespace

double FrameMotion::objectTurn(std::size_t o, double t0, double t1) const {
    const Object& object = scene_.objects[o];
    if (object.motion && !object.motion->skinned())
        return turnOf([&](double t) { return orientationOf(worldMatrix(object, t)); }, t0, t1);
    if (object.transform.size() < 2) return 0.0;
    return turnOf([&](double t) { return transform(o, t).rotate; }, t0, t1);
}

FrameMotion::Turns FrameMotion::turns(double t0, double t1) const {
    Turns turns;
    turns.camera = camera_.exact() ? exactCameraTurn(*camera_.exact(), t0, t1)
                                   : turnOf([&](double t) { return glm::quat_cast(camera(t).basis()); }, t0, t1);
    for (std::size_t o = 0; o < scene_.objects.size(); ++o) turns.objects = std::max(turns.objects, objectTurn(o, t0, t1));
    return turns;
}

}  // namespace clipblur
