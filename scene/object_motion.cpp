#include "scene/object_motion.h"

#include <algorithm>

namespace clipblur {

namespace {

// Index i and weight w such that the value at t is lerp(key[i], key[i+1], w); w = 0 when clamped.
template <typename Key>
std::pair<std::size_t, double> bracket(const std::vector<Key>& keys, double t) {
    if (keys.size() < 2 || t <= keys.front().time) return {0, 0.0};
    if (t >= keys.back().time) return {keys.size() - 1, 0.0};
    const auto next = std::upper_bound(keys.begin(), keys.end(), t,
                                       [](double time, const Key& k) { return time < k.time; });
    const std::size_t i = static_cast<std::size_t>(next - keys.begin()) - 1;
    return {i, (t - keys[i].time) / (keys[i + 1].time - keys[i].time)};
}

}  // namespace

RigidTransform evalTransform(const std::vector<TransformKey>& keys, double t) {
    if (keys.empty()) return {};
    const auto [i, w] = bracket(keys, t);
    const TransformKey& a = keys[i];
    if (w == 0.0) return {a.translate, glm::normalize(a.rotate), a.scale};
    const TransformKey& b = keys[i + 1];
    // Unit keys first: slerp of unnormalised quaternions is not the constant-rate arc that
    // propagation differentiates.
    const glm::dquat qa = glm::normalize(a.rotate);
    glm::dquat qb = glm::normalize(b.rotate);
    if (glm::dot(qa, qb) < 0.0) qb = -qb;  // shortest arc
    return {glm::mix(a.translate, b.translate, w), glm::normalize(glm::slerp(qa, qb, w)),
            glm::mix(a.scale, b.scale, w)};
}

glm::dvec3 evalVertex(const Object& object, std::uint32_t index, double t) {
    glm::dvec3 p = object.mesh.positions[index];
    if (!object.deformation.empty()) {
        const auto [i, w] = bracket(object.deformation, t);
        p = object.deformation[i].positions[index];
        if (w != 0.0) p = glm::mix(p, object.deformation[i + 1].positions[index], w);
    }
    return evalTransform(object.transform, t).apply(p);
}

void evalVertices(const Object& object, double t, std::vector<glm::dvec3>& out) {
    const RigidTransform transform = evalTransform(object.transform, t);
    const std::size_t n = object.mesh.positions.size();
    out.resize(n);
    if (object.deformation.empty()) {
        for (std::size_t i = 0; i < n; ++i) out[i] = transform.apply(object.mesh.positions[i]);
        return;
    }
    const auto [k, w] = bracket(object.deformation, t);
    const auto& a = object.deformation[k].positions;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 p = w == 0.0 ? a[i] : glm::mix(a[i], object.deformation[k + 1].positions[i], w);
        out[i] = transform.apply(p);
    }
}

namespace {

template <typename Key, typename Same>
bool keysConstantOver(const std::vector<Key>& keys, double t0, double t1, Same same) {
    if (keys.size() < 2) return true;
    // Values at t0, t1 and at every key strictly inside must all agree.
    const auto valueAt = [&](std::size_t i) -> const Key& { return keys[i]; };
    std::size_t lo = bracket(keys, t0).first;
    std::size_t hi = std::min(bracket(keys, t1).first + 1, keys.size() - 1);
    for (std::size_t i = lo; i < hi; ++i)
        if (!same(valueAt(i), valueAt(i + 1))) return false;
    return true;
}

}  // namespace

bool isStatic(const Object& object, double t0, double t1) {
    const bool rigid = keysConstantOver(object.transform, t0, t1, [](const TransformKey& a, const TransformKey& b) {
        return a.translate == b.translate && a.scale == b.scale &&
               (a.rotate == b.rotate || a.rotate == -b.rotate);
    });
    const bool undeformed = keysConstantOver(object.deformation, t0, t1, [](const DeformationKey& a, const DeformationKey& b) {
        return a.positions == b.positions;
    });
    return rigid && undeformed;
}

}  // namespace clipblur
