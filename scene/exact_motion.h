#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/gltf_animation.h"

namespace clipblur {

// The glTF animation data that exact motions point into: tracks and nodes, never changed after loading.
struct AnimationStore {
    std::deque<Track> tracks;
    std::vector<AnimatedNode> nodes;  // sized once: motions hold pointers to its elements
};

// Morph targets: object-space positions base + sum_i w_i(t) d_i, the weights from a track.
struct MorphBinding {
    const Track* weights = nullptr;
    std::vector<glm::dvec3> base;                  // the primitive's positions before any weight
    std::vector<std::vector<glm::dvec3>> targets;  // per target, an offset per vertex
};

// Linear blend skinning (glTF 2.0, 3.7.3): sum_k w_k J_k(t) IBM_k p over up to four joints per vertex.
struct SkinBinding {
    std::vector<ChainMotion> joints;        // each joint's chain, root first
    std::vector<glm::dmat4> inverse_bind;   // per joint
    std::vector<std::uint32_t> joint_ids;   // 4 per vertex
    std::vector<double> weights;            // 4 per vertex
};

class ExactMotion;

// An exact motion evaluated at one time: the world matrix of the chain (rigid objects), each joint's
// skinning matrix and the morph weights, with their time derivatives when asked for. Positions are then
// a few products per vertex.
struct ExactPose {
    const ExactMotion* motion = nullptr;
    const std::vector<glm::dvec3>* rest = nullptr;  // the mesh's positions, read where nothing morphs
    glm::dmat4 world{1.0}, world_rate{0.0};
    std::vector<glm::dmat4> joint, joint_rate;  // J_k(t) IBM_k and its derivative
    std::vector<double> weight, weight_rate;

    // World position of a vertex and its time derivative (per frame; zero when rates were not asked).
    glm::dvec3 vertex(std::uint32_t index) const;
    glm::dvec3 vertexRate(std::uint32_t index) const;
    // The matrix taking object-space normals to world space (inverse transpose of the world matrix's
    // linear part); for a skin the identity (its normals are turned with the faces).
    glm::dmat3 normalMatrix() const;

private:
    glm::dvec3 objectSpace(std::uint32_t index) const;
    glm::dvec3 objectSpaceRate(std::uint32_t index) const;
};

// The true glTF motion of one object, followed at whatever time is asked: a chain of animated nodes
// (any sampler, any scale, shear included), morph weights, a skin. Shared and immutable; the object's
// mesh holds the rest pose (rest weights, bind space for a skin).
class ExactMotion {
public:
    ExactMotion(std::shared_ptr<const AnimationStore> store, ChainMotion chain);

    void setMorph(MorphBinding morph);
    void setSkin(SkinBinding skin);

    bool deforms() const { return morph_.weights || !skin_.joints.empty(); }
    bool skinned() const { return !skin_.joints.empty(); }
    // Every key time of every track, sorted: between two of them every track follows one polynomial or
    // slerp arc, so stillness, breakpoints and motion comparisons are decided by them.
    const std::vector<double>& keyTimes() const { return key_times_; }
    // True when no track changes value over [t0, t1]: the pose there is the pose at t0.
    bool constantOver(double t0, double t1) const;

    enum class Rates { Skip, Compute };
    // The pose at t of a mesh whose rest positions are `rest` (kept alive by the caller). With `vertices`
    // given, only the joints those vertices use are evaluated (a triangle's pose costs at most 12 joints);
    // the pose then answers for those vertices alone.
    ExactPose pose(const std::vector<glm::dvec3>& rest, double t, Rates rates,
                   std::span<const std::uint32_t> vertices = {}) const;

    // The chain's world matrix (not made rigid) and, when `rate` is given, its time derivative.
    glm::dmat4 world(double t, glm::dmat4* rate = nullptr) const { return chain_.product(t, rate); }

    const MorphBinding& morph() const { return morph_; }
    const SkinBinding& skin() const { return skin_; }

private:
    void addTracks(const ChainMotion& chain);

    std::shared_ptr<const AnimationStore> store_;
    ChainMotion chain_;
    MorphBinding morph_;
    SkinBinding skin_;
    std::vector<const Track*> tracks_;
    std::vector<double> key_times_;
};

}  // namespace clipblur
