#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "scene/camera.h"
#include "scene/exact_motion.h"

namespace clipblur {

// How fast the camera moves at one time, per frame: d rc / dt, and the angular velocity of its basis
// (d e_i / dt = angular_velocity x e_i).
struct CameraRates {
    glm::dvec3 velocity{0.0};
    glm::dvec3 angular_velocity{0.0};
};

// The glTF convention applied to a world matrix: the camera sits at its translation, looks along its -Z
// column with its +Y column as up. Only those two directions are read, so a scaled or sheared matrix
// still defines a camera (its view and up made orthonormal by makeCameraFrame); it throws a scene
// error where the -Z column is zero or parallel to the +Y column.
CameraFrame cameraFrameOf(const glm::dmat4& world);

// A glTF camera whose motion keys cannot hold exactly (an animated ancestor, CUBICSPLINE, more keys than
// allowed), followed at whatever time is asked: the node chain and its tracks, as ExactMotion follows
// objects. Shared and immutable.
class ExactCamera {
public:
    ExactCamera(std::shared_ptr<const AnimationStore> store, ChainMotion chain);

    // cameraFrameOf(world(t)); with `rates`, the frame's analytic rates (right derivatives at key times).
    CameraFrame at(double t, CameraRates* rates = nullptr) const;
    // Every key time of every track on the chain: between two of them every track is one polynomial or
    // slerp arc, so the camera's motion is smooth there.
    const std::vector<double>& keyTimes() const { return motion_.keyTimes(); }
    // Position and orientation are the same at every time of [t0, t1].
    bool constantOver(double t0, double t1) const { return motion_.constantOver(t0, t1); }
    // The position is the same at every time of [t0, t1]: no track that can move it changes there.
    bool eyeConstantOver(double t0, double t1) const;

private:
    ExactMotion motion_;
    std::vector<const Track*> eye_tracks_;
};

}  // namespace clipblur
