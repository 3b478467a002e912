#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "renderer/camera_path.h"
#include "scene/object_motion.h"
#include "scene/scene.h"

namespace clipblur {

// Which parts of the scene move during one window of time (the shutter, or a segment of it), read off the
// keys once. Still means no key differs inside the window, so the pose at any time of it is the pose at t0.
struct MotionWindow {
    double t0 = 0.0, t1 = 0.0;
    bool camera_still = true;      // position and orientation
    bool eye_still = true;         // position only: a camera that only turns sees the same surfaces
    std::vector<char> object_still;  // per object: no transform or deformation key differs

    bool objectStill(std::size_t object) const { return object_still[object] != 0; }
    // The object stands still in the image: it and the camera keep their poses.
    bool stillInImage(std::size_t object) const { return camera_still && objectStill(object); }
    bool anyObjectMoves() const;
    // Nothing moves: the window's first image is the whole answer.
    bool still() const { return camera_still && !anyObjectMoves(); }
};

// One frame's motion, built once per frame and passed to every stage: the camera at any time, which
// objects move over the shutter and over any segment of it, their poses, motion groups and turns. No
// stage asks the scene's keys whether something moves.
class FrameMotion {
public:
    FrameMotion(const Scene& scene, double t0, double t1);

    const Scene& scene() const { return scene_; }
    double t0() const { return shutter_.t0; }
    double t1() const { return shutter_.t1; }
    const MotionWindow& shutter() const { return shutter_; }
    // A window inside the shutter: what is still over the whole shutter is still there without asking.
    MotionWindow window(double a, double b) const;

    // Exactly (bit for bit) evalCamera, without re-deriving the keys' frames.
    CameraFrame camera(double t) const { return camera_.at(t); }
    const CameraPath& cameraPath() const { return camera_; }
    RigidTransform transform(std::size_t object, double t) const;
    // World positions of every vertex of an object at time t (evalVertices).
    void vertices(std::size_t object, double t, std::vector<glm::dvec3>& out) const;

    // Objects grouped by how they move over the window (motionGroups): per object its group's first object.
    std::vector<std::uint32_t> groups(const MotionWindow& window) const;
    // The rotation (radians) the camera turns through over [t0, t1], and the largest any object turns
    // through (objectTurn), each summed along the motion.
    struct Turns {
        double camera = 0.0;
        double objects = 0.0;
    };
    Turns turns(double t0, double t1) const;
    // The rotation (radians) object o turns through over [t0, t1]: its exact motion's, else its transform
    // keys' (0 with fewer than two).
    double objectTurn(std::size_t o, double t0, double t1) const;

private:
    MotionWindow windowOf(double a, double b, const MotionWindow* outer) const;

    const Scene& scene_;
    CameraPath camera_;
    MotionWindow shutter_;
};

}  // namespace clipblur
