#include "scene/object_motion.h"

#include <algorithm>
#include <array>
#include <limits>

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

bool deformsOver(const Object& object, double t0, double t1) {
    return !keysConstantOver(object.deformation, t0, t1, [](const DeformationKey& a, const DeformationKey& b) {
        return a.positions == b.positions;
    });
}

bool isStatic(const Object& object, double t0, double t1) {
    const bool rigid = keysConstantOver(object.transform, t0, t1, [](const TransformKey& a, const TransformKey& b) {
        return a.translate == b.translate && a.scale == b.scale &&
               (a.rotate == b.rotate || a.rotate == -b.rotate);
    });
    return rigid && !deformsOver(object, t0, t1);
}

namespace {

// The times at which motions are compared: t0, t1, every transform key inside, and three times inside each
// gap between them. Inside a gap no object passes a key, so each moves along one arc (translation and
// scale linear, rotation at a constant rate); two different arcs that agree at both ends and three inner
// times would be a coincidence that real keys do not make.
std::vector<double> comparisonTimes(const Scene& scene, double t0, double t1) {
    std::vector<double> keys{t0, t1};
    for (const Object& object : scene.objects)
        for (const TransformKey& key : object.transform)
            if (key.time > t0 && key.time < t1) keys.push_back(key.time);
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<double> times;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        times.push_back(keys[i]);
        if (i + 1 < keys.size())
            for (int j = 1; j <= 3; ++j) times.push_back(keys[i] + (keys[i + 1] - keys[i]) * j / 4.0);
    }
    return times;
}

}  // namespace

std::vector<std::uint32_t> motionGroups(const Scene& scene, double t0, double t1) {
    // An affine map is fixed by four points that are not coplanar: a corner of the scene's box and one
    // step along each axis, a step as long as the box, so that differences are measured at its scale.
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const Object& object : scene.objects) {
        const RigidTransform start = evalTransform(object.transform, t0);
        for (const glm::dvec3& p : object.mesh.positions) {
            lo = glm::min(lo, start.apply(p));
            hi = glm::max(hi, start.apply(p));
        }
    }
    const glm::dvec3 size = hi - lo;
    const double extent = std::max({1.0, size.x, size.y, size.z});
    const glm::dvec3 origin = glm::all(glm::lessThanEqual(lo, hi)) ? lo : glm::dvec3(0.0);
    const std::array<glm::dvec3, 4> points{origin, origin + glm::dvec3(extent, 0, 0), origin + glm::dvec3(0, extent, 0),
                                           origin + glm::dvec3(0, 0, extent)};
    // Where each object's motion carries the points: with p = T(t0)^-1 q fixed, T(t) p for every time.
    const std::vector<double> times = comparisonTimes(scene, t0, t1);
    const auto track = [&](const Object& object) {
        const RigidTransform start = evalTransform(object.transform, t0);
        std::vector<glm::dvec3> out;
        for (const glm::dvec3& q : points) {
            const glm::dvec3 p = glm::inverse(start.rotate) * (q - start.translate) / start.scale;
            for (const double t : times) out.push_back(evalTransform(object.transform, t).apply(p));
        }
        return out;
    };
    // Rounding in the slerp and the inverse is far below this; any real difference in motion is far above.
    const double tolerance = 1e-9 * extent;
    std::vector<std::uint32_t> group(scene.objects.size());
    std::vector<std::uint32_t> leaders;
    std::vector<std::vector<glm::dvec3>> tracks;
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        group[o] = o;
        // A deforming object, or one squashed flat at t0 (no inverse), keeps a group of its own.
        const glm::dvec3 scale = evalTransform(object.transform, t0).scale;
        if (deformsOver(object, t0, t1) || scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0) continue;
        std::vector<glm::dvec3> mine = track(object);
        const auto same = [&](const std::vector<glm::dvec3>& other) {
            for (std::size_t i = 0; i < mine.size(); ++i)
                if (glm::length(mine[i] - other[i]) > tolerance) return false;
            return true;
        };
        std::size_t k = 0;
        while (k < tracks.size() && !same(tracks[k])) ++k;
        if (k < tracks.size()) {
            group[o] = leaders[k];
        } else {
            leaders.push_back(o);
            tracks.push_back(std::move(mine));
        }
    }
    return group;
}

}  // namespace clipblur
