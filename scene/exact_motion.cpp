#include "scene/exact_motion.h"

#include <algorithm>

namespace clipblur {

ExactMotion::ExactMotion(std::shared_ptr<const AnimationStore> store, ChainMotion chain)
    : store_(std::move(store)), chain_(std::move(chain)) {
    addTracks(chain_);
}

void ExactMotion::addTracks(const ChainMotion& chain) {
    for (const AnimatedNode* node : chain.chain)
        for (const Track* t : {node->translation, node->rotation, node->scale})
            if (t && std::find(tracks_.begin(), tracks_.end(), t) == tracks_.end()) {
                tracks_.push_back(t);
                key_times_.insert(key_times_.end(), t->times.begin(), t->times.end());
            }
    std::sort(key_times_.begin(), key_times_.end());
    key_times_.erase(std::unique(key_times_.begin(), key_times_.end()), key_times_.end());
}

void ExactMotion::setMorph(MorphBinding morph) {
    morph_ = std::move(morph);
    if (!morph_.weights) return;
    tracks_.push_back(morph_.weights);
    key_times_.insert(key_times_.end(), morph_.weights->times.begin(), morph_.weights->times.end());
    std::sort(key_times_.begin(), key_times_.end());
    key_times_.erase(std::unique(key_times_.begin(), key_times_.end()), key_times_.end());
}

void ExactMotion::setSkin(SkinBinding skin) {
    skin_ = std::move(skin);
    for (const ChainMotion& joint : skin_.joints) addTracks(joint);
}

bool ExactMotion::constantOver(double t0, double t1) const {
    return std::all_of(tracks_.begin(), tracks_.end(), [&](const Track* t) { return t->constantOver(t0, t1); });
}

ExactPose ExactMotion::pose(const std::vector<glm::dvec3>& rest, double t, Rates rates,
                            std::span<const std::uint32_t> vertices) const {
    const bool with_rates = rates == Rates::Compute;
    ExactPose p;
    p.motion = this;
    p.rest = &rest;
    p.world = chain_.product(t, with_rates ? &p.world_rate : nullptr);
    if (morph_.weights) {
        const std::size_t n = morph_.weights->width;
        p.weight.resize(n);
        p.weight_rate.assign(n, 0.0);
        morph_.weights->eval(t, p.weight.data(), with_rates ? p.weight_rate.data() : nullptr);
    }
    p.joint.assign(skin_.joints.size(), glm::dmat4(0.0));
    p.joint_rate.assign(skin_.joints.size(), glm::dmat4(0.0));
    std::vector<char> used(skin_.joints.size(), vertices.empty() ? 1 : 0);
    for (const std::uint32_t v : vertices)
        for (std::size_t k = 0; k < 4; ++k)
            if (!skin_.joints.empty() && skin_.weights[4 * v + k] != 0.0) used[skin_.joint_ids[4 * v + k]] = 1;
    for (std::size_t j = 0; j < skin_.joints.size(); ++j) {
        if (!used[j]) continue;
        glm::dmat4 rate;
        p.joint[j] = skin_.joints[j].product(t, with_rates ? &rate : nullptr) * skin_.inverse_bind[j];
        if (with_rates) p.joint_rate[j] = rate * skin_.inverse_bind[j];
    }
    return p;
}

glm::dvec3 ExactPose::objectSpace(std::uint32_t index) const {
    const MorphBinding& morph = motion->morph();
    if (!morph.weights) return (*rest)[index];
    glm::dvec3 p = morph.base[index];
    for (std::size_t i = 0; i < weight.size() && i < morph.targets.size(); ++i) p += weight[i] * morph.targets[i][index];
    return p;
}

glm::dvec3 ExactPose::objectSpaceRate(std::uint32_t index) const {
    const MorphBinding& morph = motion->morph();
    glm::dvec3 r(0.0);
    for (std::size_t i = 0; i < weight_rate.size() && i < morph.targets.size(); ++i) r += weight_rate[i] * morph.targets[i][index];
    return r;
}

namespace {

glm::dvec3 point(const glm::dmat4& m, const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }
glm::dvec3 direction(const glm::dmat4& m, const glm::dvec3& d) { return glm::dvec3(m * glm::dvec4(d, 0.0)); }

}  // namespace

glm::dvec3 ExactPose::vertex(std::uint32_t index) const {
    const glm::dvec3 local = objectSpace(index);
    const SkinBinding& skin = motion->skin();
    if (skin.joints.empty()) return point(world, local);
    glm::dvec3 out(0.0);
    for (std::size_t k = 0; k < 4; ++k) {
        const double w = skin.weights[4 * index + k];
        if (w != 0.0) out += w * point(joint[skin.joint_ids[4 * index + k]], local);
    }
    return out;
}

glm::dvec3 ExactPose::vertexRate(std::uint32_t index) const {
    const glm::dvec3 local = objectSpace(index);
    const glm::dvec3 local_rate = objectSpaceRate(index);
    const SkinBinding& skin = motion->skin();
    if (skin.joints.empty()) return point(world_rate, local) + direction(world, local_rate);
    glm::dvec3 out(0.0);
    for (std::size_t k = 0; k < 4; ++k) {
        const double w = skin.weights[4 * index + k];
        const std::uint32_t j = skin.joint_ids[4 * index + k];
        if (w != 0.0) out += w * (point(joint_rate[j], local) + direction(joint[j], local_rate));
    }
    return out;
}

glm::dmat3 ExactPose::normalMatrix() const {
    if (!motion->skin().joints.empty()) return glm::dmat3(1.0);
    return glm::transpose(glm::inverse(glm::dmat3(world)));
}

}  // namespace clipblur
