#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace clipblur {

// Object-to-world transform at one time, decomposed so that rotation follows its slerp arc.
struct RigidTransform {
    glm::dvec3 translate{0.0};
    glm::dquat rotate{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};

    glm::dvec3 apply(const glm::dvec3& p) const { return translate + rotate * (scale * p); }
};

// Translation and scale linear, rotation slerped between the keys that bracket t; held outside them.
RigidTransform evalTransform(const std::vector<TransformKey>& keys, double t);

// World position of vertex `index` of `object` at absolute time t: deformation keys interpolated
// linearly in object space, then the transform at t applied.
glm::dvec3 evalVertex(const Object& object, std::uint32_t index, double t);

// World positions of the three vertices of triangle `triangle` at time t (one motion evaluation).
void evalTriangle(const Object& object, std::uint32_t triangle, double t, glm::dvec3 out[3]);

// World positions of every vertex of `object` at time t (one transform evaluation for the whole mesh).
void evalVertices(const Object& object, double t, std::vector<glm::dvec3>& out);

// The object-to-world matrix at t: the keys' transform, or an exact motion's world matrix (which may
// carry shear); a skinned object's is the identity.
glm::dmat4 worldMatrix(const Object& object, double t);

// The matrix taking the object's normals to world space at t: the inverse transpose of worldMatrix's
// linear part (the identity for a skin, whose normals the shader turns with its faces).
glm::dmat3 normalMatrix(const Object& object, double t);

// True when the object changes shape at some time: deformation keys, morph targets or a skin.
bool deforms(const Object& object);

// Times strictly inside (t0, t1) where the object's motion changes its interpolating piece: transform
// and deformation key times, or every key time of an exact motion's tracks.
void addMotionKeyTimes(const Object& object, double t0, double t1, std::vector<double>& times);

// True when the object's deformation keys differ inside [t0, t1].
bool deformsOver(const Object& object, double t0, double t1);

// True when the object has no motion inside [t0, t1] (no keys differ there).
bool isStatic(const Object& object, double t0, double t1);

// Objects grouped by how they move over [t0, t1], per object the index of its group's first object. Two
// objects share a group when neither deforms there and their world motions T(t) T(t0)^-1 agree at every
// time of [t0, t1]: nothing of one then moves relative to the other, whatever the camera does, so how a
// surface was cut into objects cannot change what the renderer counts as relative motion.
std::vector<std::uint32_t> motionGroups(const Scene& scene, double t0, double t1);

}  // namespace clipblur
