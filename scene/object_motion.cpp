#include "scene/object_motion.h"

#include <algorithm>
#include <array>
#include <limits>

#include "scene/exact_motion.h"

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
    if (object.motion) {
        const std::uint32_t only[1] = {index};
        return object.motion->pose(object.mesh.positions, t, ExactMotion::Rates::Skip, only).vertex(index);
    }
    glm::dvec3 p = object.mesh.positions[index];
    if (!object.deformation.empty()) {
        const auto [i, w] = bracket(object.deformation, t);
        p = object.deformation[i].positions[index];
        if (w != 0.0) p = glm::mix(p, object.deformation[i + 1].positions[index], w);
    }
    return evalTransform(object.transform, t).apply(p);
}

void evalTriangle(const Object& object, std::uint32_t triangle, double t, glm::dvec3 out[3]) {
    const auto& tri = object.mesh.triangles[triangle];
    if (!object.motion) {
        for (int k = 0; k < 3; ++k) out[k] = evalVertex(object, tri[k], t);
        return;
    }
    const ExactPose pose = object.motion->pose(object.mesh.positions, t, ExactMotion::Rates::Skip, tri);
    for (int k = 0; k < 3; ++k) out[k] = pose.vertex(tri[k]);
}

void evalVertices(const Object& object, double t, std::vector<glm::dvec3>& out) {
    if (object.motion) {
        const ExactPose pose = object.motion->pose(object.mesh.positions, t, ExactMotion::Rates::Skip);
        out.resize(object.mesh.positions.size());
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = pose.vertex(static_cast<std::uint32_t>(i));
        return;
    }
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

glm::dmat4 worldMatrix(const Object& object, double t) {
    if (object.motion && object.motion->skinned()) return glm::dmat4(1.0);
    if (object.motion) return object.motion->pose(object.mesh.positions, t, ExactMotion::Rates::Skip).world;
    const RigidTransform x = evalTransform(object.transform, t);
    return trsMatrix(x);
}

glm::dmat3 normalMatrix(const Object& object, double t) {
    if (object.motion && object.motion->skinned()) return glm::dmat3(1.0);
    if (object.motion) return object.motion->pose(object.mesh.positions, t, ExactMotion::Rates::Skip).normalMatrix();
    return glm::transpose(glm::inverse(glm::dmat3(worldMatrix(object, t))));
}

bool deforms(const Object& object) { return !object.deformation.empty() || (object.motion && object.motion->deforms()); }

void addMotionKeyTimes(const Object& object, double t0, double t1, std::vector<double>& times) {
    const auto add = [&](double t) {
        if (t > t0 && t < t1) times.push_back(t);
    };
    for (const TransformKey& k : object.transform) add(k.time);
    for (const DeformationKey& k : object.deformation) add(k.time);
    if (object.motion)
        for (const double t : object.motion->keyTimes()) add(t);
}

bool deformsOver(const Object& object, double t0, double t1) {
    if (object.motion) return object.motion->deforms() && !object.motion->constantOver(t0, t1);
    return !keysConstantOver(object.deformation, t0, t1, [](const DeformationKey& a, const DeformationKey& b) {
        return a.positions == b.positions;
    });
}

bool isStatic(const Object& object, double t0, double t1) {
    if (object.motion) return object.motion->constantOver(t0, t1);
    const bool rigid = keysConstantOver(object.transform, t0, t1, [](const TransformKey& a, const TransformKey& b) {
        return a.translate == b.translate && a.scale == b.scale &&
               (a.rotate == b.rotate || a.rotate == -b.rotate);
    });
    return rigid && !deformsOver(object, t0, t1);
}

namespace {

// The times at which motions are compared: t0, t1, every key inside, and three times inside each gap
// between them. Inside a gap no object passes a key, so each moves along one arc (translation and scale
// linear, rotation at a constant rate) or, for an exact glTF motion, one product of polynomials and slerp
// arcs; two different such motions that agree at both ends and three inner times would be a coincidence
// that real animation does not make.
std::vector<double> comparisonTimes(const Scene& scene, double t0, double t1) {
    std::vector<double> keys{t0, t1};
    for (const Object& object : scene.objects) addMotionKeyTimes(object, t0, t1, keys);
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
    std::vector<glm::dvec3> world;
    for (const Object& object : scene.objects) {
        // Keyed objects by their rest mesh under the transform (deformation aside), exact ones as posed.
        if (object.motion) {
            evalVertices(object, t0, world);
        } else {
            const RigidTransform start = evalTransform(object.transform, t0);
            world.clear();
            for (const glm::dvec3& p : object.mesh.positions) world.push_back(start.apply(p));
        }
        for (const glm::dvec3& p : world) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
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
        std::vector<glm::dvec3> out;
        if (object.motion) {
            const glm::dmat4 inverse = glm::inverse(worldMatrix(object, t0));
            std::vector<glm::dmat4> at;
            for (const double t : times) at.push_back(worldMatrix(object, t));
            for (const glm::dvec3& q : points) {
                const glm::dvec4 p = inverse * glm::dvec4(q, 1.0);
                for (const glm::dmat4& m : at) out.push_back(glm::dvec3(m * p));
            }
            return out;
        }
        const RigidTransform start = evalTransform(object.transform, t0);
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
        // A deforming object (a skin even when still: its joints are not one matrix), or one squashed flat at
        // t0 (no inverse), keeps a group of its own.
        const glm::dvec3 scale = evalTransform(object.transform, t0).scale;
        const bool flat = object.motion ? !(std::abs(glm::determinant(glm::dmat3(worldMatrix(object, t0)))) > 0.0)
                                        : scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0;
        const bool skin = object.motion && object.motion->skinned();
        if (deformsOver(object, t0, t1) || flat || skin) continue;
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
