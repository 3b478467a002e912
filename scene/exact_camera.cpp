#include "scene/exact_camera.h"

#include <algorithm>

namespace clipblur {

namespace {

bool movesOrigin(const AnimatedNode& node) {
    if (node.has_matrix) return glm::dvec3(node.matrix[3]) != glm::dvec3(0.0);
    return node.translation || node.rest.translate != glm::dvec3(0.0);
}

// The tracks that can move the camera's position, the image of the tail's origin under the chain: every
// translation, and a node's rotation and scale only when the point below it may be off its origin.
// Conservative: a track listed may still leave the position where it is.
std::vector<const Track*> eyeTracks(const ChainMotion& chain) {
    std::vector<const Track*> tracks;
    bool offset = glm::dvec3(chain.tail[3]) != glm::dvec3(0.0);
    for (auto node = chain.chain.rbegin(); node != chain.chain.rend(); ++node) {
        const AnimatedNode& n = **node;
        if (n.translation) tracks.push_back(n.translation);
        if (offset)
            for (const Track* t : {n.rotation, n.scale})
                if (t) tracks.push_back(t);
        offset = offset || movesOrigin(n);
    }
    return tracks;
}

// d/dt of x / |x|.
glm::dvec3 unitRate(const glm::dvec3& unit, double length, const glm::dvec3& rate) {
    return (rate - unit * glm::dot(unit, rate)) / length;
}

}  // namespace

CameraFrame cameraFrameOf(const glm::dmat4& world) {
    return makeCameraFrame(glm::dvec3(world[3]), -glm::dvec3(world[2]), glm::dvec3(world[1]));
}

ExactCamera::ExactCamera(std::shared_ptr<const AnimationStore> store, ChainMotion chain)
    : motion_(std::move(store), chain), eye_tracks_(eyeTracks(chain)) {}

bool ExactCamera::eyeConstantOver(double t0, double t1) const {
    return std::all_of(eye_tracks_.begin(), eye_tracks_.end(), [&](const Track* t) { return t->constantOver(t0, t1); });
}

CameraFrame ExactCamera::at(double t, CameraRates* rates) const {
    glm::dmat4 rate;
    const glm::dmat4 world = motion_.world(t, rates ? &rate : nullptr);
    const CameraFrame f = cameraFrameOf(world);
    if (!rates) return f;
    // Differentiate makeCameraFrame: e3 = v / |v| with v = -Z column, e1 = w / |w| with
    // w = u - e3 (u . e3), u = +Y column, e2 = e3 x e1.
    const glm::dvec3 v = -glm::dvec3(world[2]), u(world[1]);
    const glm::dvec3 e3_rate = unitRate(f.e3, glm::length(v), -glm::dvec3(rate[2]));
    const glm::dvec3 u_rate(rate[1]);
    const glm::dvec3 w = u - f.e3 * glm::dot(u, f.e3);
    const glm::dvec3 w_rate = u_rate - e3_rate * glm::dot(u, f.e3) - f.e3 * (glm::dot(u_rate, f.e3) + glm::dot(u, e3_rate));
    const glm::dvec3 e1_rate = unitRate(f.e1, glm::length(w), w_rate);
    const glm::dvec3 e2_rate = glm::cross(e3_rate, f.e1) + glm::cross(f.e3, e1_rate);
    rates->velocity = glm::dvec3(rate[3]);
    // For an orthonormal basis turning with e_i' = W x e_i: sum_i e_i x e_i' = 2 W.
    rates->angular_velocity =
        0.5 * (glm::cross(f.e1, e1_rate) + glm::cross(f.e2, e2_rate) + glm::cross(f.e3, e3_rate));
    return f;
}

}  // namespace clipblur
