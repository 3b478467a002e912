#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/object_motion.h"

namespace clipblur {

// A glTF node's local translation, rotation and scale (T R S) as a matrix.
glm::dmat4 trsMatrix(const RigidTransform& trs);

enum class Interpolation { Linear, Step, CubicSpline };

// One glTF animation sampler bound to one node property, times already in frames. Values hold `width`
// numbers per key, or 3 * width for CubicSpline (in-tangent, value, out-tangent), tangents per frame.
// Rotations (width 4, x y z w) are slerped along the shortest arc and come out unit length.
struct Track {
    Interpolation interpolation = Interpolation::Linear;
    std::size_t width = 3;
    bool rotation = false;
    std::vector<double> times;   // strictly increasing
    std::vector<double> values;

    // The value at t (held outside the keys), `width` numbers written to out; with `rate`, also its time
    // derivative per frame (the right derivative at a key time, zero where held or STEP). A rotation's
    // rate is d/dt of the unit quaternion written to out.
    void eval(double t, double* out, double* rate = nullptr) const;
    // True when the value is the same at every time of [t0, t1] (judged from the keys, conservatively).
    bool constantOver(double t0, double t1) const;
};

// A node's place in the hierarchy: its rest pose or matrix and the tracks that animate it.
struct AnimatedNode {
    RigidTransform rest;
    glm::dmat4 matrix{1.0};
    bool has_matrix = false;  // glTF forbids animating a node given by a matrix
    const Track* translation = nullptr;
    const Track* rotation = nullptr;
    const Track* scale = nullptr;

    bool animated() const { return translation || rotation || scale; }
    glm::dmat4 local(double t) const;
    // local(t) and, when `rate` is given, its time derivative (per frame).
    glm::dmat4 local(double t, glm::dmat4* rate) const;
};

// Object-to-world motion of a chain of nodes, root first, ending at the deepest animated node (the static
// nodes below it are folded into the mesh by the caller).
// A camera keeps a static tail (nodes below the animated one) and is made rigid: position, -Z view and
// +Y up made orthogonal to it, whatever scale the nodes carry.
struct ChainMotion {
    std::vector<const AnimatedNode*> chain;
    glm::dmat4 tail{1.0};
    bool rigid = false;
    glm::dmat4 world(double t) const;
    // The product of the chain's local matrices and tail (not made rigid) and its time derivative by the
    // product rule; `rate` may be null.
    glm::dmat4 product(double t, glm::dmat4* rate) const;
};

// Throws std::domain_error when m has shear (non-uniform scale under a rotation) or is singular.
RigidTransform decomposeMatrix(const glm::dmat4& m);

// What key generation may assume and must meet.
struct KeyPlan {
    std::vector<double> times;       // every key time of every track on the chain, and STEP holds
    std::vector<bool> jump_after;    // per times[i]: [times[i], times[i+1]] is a STEP jump window
    bool exact = false;              // the keys at `times` reproduce the motion exactly
};

// Within a STEP jump window the keys move linearly from the held value to the next one.
inline constexpr double kStepWindowFrames = 1e-3;

// Key times for a chain: exact when one node animates, the last of the chain, without CUBICSPLINE,
// under static ancestors whose product has uniform scale, and without a tail (then
// P * T(t) R(t) S(t) is again a translation linear in t, P's rotation times a slerp, which is a slerp,
// and a uniformly scaled linear scale).
KeyPlan planKeys(const ChainMotion& motion);

// The key times of some tracks and their STEP holds (`exact` left false).
KeyPlan planTimes(const std::vector<const Track*>& tracks);

// Transform keys following world(t) * points: exact at plan.times; between them, when the plan is not
// exact, intervals are bisected until the keys' deviation from the true motion at the interval's
// quarter points, measured at `corners` (the mesh's bounding box: deviation is affine in the point, so
// a box corner bounds it), is at most tolerance. Throws std::length_error past max_keys.
struct ResampleSpec {
    std::vector<glm::dvec3> corners;
    double tolerance = 0.0;
    std::size_t max_keys = 0;
};
std::vector<TransformKey> followChain(const ChainMotion& motion, const KeyPlan& plan, const ResampleSpec& spec);

}  // namespace clipblur
