#include "scene/gltf_animation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

namespace clipblur {

namespace {

// Index of the key at or before t; t must lie inside [times.front(), times.back()).
std::size_t keyBefore(const std::vector<double>& times, double t) {
    const auto next = std::upper_bound(times.begin(), times.end(), t);
    return static_cast<std::size_t>(next - times.begin()) - 1;
}

glm::dquat quatAt(const double* v) { return glm::dquat(v[3], v[0], v[1], v[2]); }

void writeQuat(const glm::dquat& q, double* out) {
    out[0] = q.x;
    out[1] = q.y;
    out[2] = q.z;
    out[3] = q.w;
}

}  // namespace

glm::dmat4 trsMatrix(const RigidTransform& trs) {
    return glm::translate(glm::dmat4(1.0), trs.translate) * glm::mat4_cast(trs.rotate) *
           glm::scale(glm::dmat4(1.0), trs.scale);
}

void Track::eval(double t, double* out, double* rate) const {
    const std::size_t stride = interpolation == Interpolation::CubicSpline ? 3 * width : width;
    const std::size_t value_at = interpolation == Interpolation::CubicSpline ? width : 0;
    const auto value = [&](std::size_t k) { return values.data() + k * stride + value_at; };
    std::size_t k = 0;
    double u = 0.0;
    if (t >= times.back()) {
        k = times.size() - 1;
    } else if (t > times.front()) {
        k = keyBefore(times, t);
        u = (t - times[k]) / (times[k + 1] - times[k]);
    }
    // Moving: inside the keys (a key time itself counts, for its right derivative) and not STEP.
    const bool moving = rate && interpolation != Interpolation::Step && t >= times.front() && t < times.back();
    if (rate) std::fill(rate, rate + width, 0.0);
    if (!moving && (u == 0.0 || interpolation == Interpolation::Step)) {
        std::copy(value(k), value(k) + width, out);
        if (rotation) writeQuat(glm::normalize(quatAt(out)), out);
        return;
    }
    const double dt = times[k + 1] - times[k];
    if (interpolation == Interpolation::CubicSpline) {
        // glTF 2.0 Appendix C: the cubic Hermite spline, tangents scaled by the key interval.
        const double u2 = u * u;
        const double u3 = u2 * u;
        const double h00 = 2 * u3 - 3 * u2 + 1;
        const double h10 = dt * (u3 - 2 * u2 + u);
        const double h01 = -2 * u3 + 3 * u2;
        const double h11 = dt * (u3 - u2);
        const double* out_tangent = values.data() + k * stride + 2 * width;
        const double* in_tangent = values.data() + (k + 1) * stride;
        double n[4] = {0, 0, 0, 0};
        for (std::size_t i = 0; i < width; ++i) {
            n[i % 4] = out[i] = h00 * value(k)[i] + h10 * out_tangent[i] + h01 * value(k + 1)[i] + h11 * in_tangent[i];
            if (rate)
                rate[i] = (6 * u2 - 6 * u) * (value(k)[i] - value(k + 1)[i]) / dt + (3 * u2 - 4 * u + 1) * out_tangent[i] +
                          (3 * u2 - 2 * u) * in_tangent[i];
        }
        if (!rotation) return;
        // q = n / |n|: q' = (n' - q (q . n')) / |n|.
        const glm::dquat raw = quatAt(n);
        const glm::dquat q = glm::normalize(raw);
        writeQuat(q, out);
        if (rate) {
            const glm::dquat d = quatAt(rate);
            writeQuat((d - q * glm::dot(q, d)) / glm::length(raw), rate);
        }
        return;
    }
    if (rotation) {
        const glm::dquat a = glm::normalize(quatAt(value(k)));
        glm::dquat b = glm::normalize(quatAt(value(k + 1)));
        if (glm::dot(a, b) < 0.0) b = -b;  // glTF's slerp takes the shortest arc, as the renderer's does
        const glm::dquat q = u == 0.0 ? a : glm::normalize(glm::slerp(a, b, u));
        writeQuat(q, out);
        // slerp(a, b, u) = (b a^-1)^u a turns about the world axis of b a^-1 at a constant rate:
        // q' = (0, omega) q / 2.
        if (rate) {
            const glm::dquat relative = b * glm::conjugate(a);
            const glm::dvec3 v(relative.x, relative.y, relative.z);
            const double s = glm::length(v);
            const glm::dvec3 omega = s > 0.0 ? v * (2.0 * std::atan2(s, relative.w) / s / dt) : glm::dvec3(0.0);
            writeQuat(0.5 * (glm::dquat(0.0, omega.x, omega.y, omega.z) * q), rate);
        }
        return;
    }
    for (std::size_t i = 0; i < width; ++i) {
        out[i] = value(k)[i] + u * (value(k + 1)[i] - value(k)[i]);
        if (rate) rate[i] = (value(k + 1)[i] - value(k)[i]) / dt;
    }
}

bool Track::constantOver(double t0, double t1) const {
    if (times.size() < 2 || t1 <= times.front() || t0 >= times.back()) return true;
    const auto at_or_before = [&](double t) { return t <= times.front() ? 0 : keyBefore(times, std::min(t, times.back())); };
    const std::size_t first = at_or_before(t0);
    // STEP takes the value of the key at or before each time; the others also reach toward the next key.
    std::size_t last = at_or_before(t1);
    if (interpolation != Interpolation::Step && times[last] < t1) ++last;
    const std::size_t stride = interpolation == Interpolation::CubicSpline ? 3 * width : width;
    const std::size_t value_at = interpolation == Interpolation::CubicSpline ? width : 0;
    for (std::size_t k = first; k <= last; ++k)
        for (std::size_t i = 0; i < width; ++i) {
            if (values[k * stride + value_at + i] != values[first * stride + value_at + i]) return false;
            if (interpolation != Interpolation::CubicSpline) continue;
            // The tangents that shape [first, last]: out of every key but the last, into every key but the first.
            if (k < last && values[k * stride + 2 * width + i] != 0.0) return false;
            if (k > first && values[k * stride + i] != 0.0) return false;
        }
    return true;
}

glm::dmat4 AnimatedNode::local(double t) const { return local(t, nullptr); }

glm::dmat4 AnimatedNode::local(double t, glm::dmat4* rate) const {
    if (rate) *rate = glm::dmat4(0.0);
    if (has_matrix) return matrix;
    RigidTransform trs = rest;
    double v[4];
    double r[4] = {0, 0, 0, 0};
    double* want = rate ? r : nullptr;
    glm::dvec3 translate_rate(0.0), scale_rate(0.0);
    glm::dquat rotate_rate(0.0, 0.0, 0.0, 0.0);
    if (translation) {
        translation->eval(t, v, want);
        trs.translate = {v[0], v[1], v[2]};
        translate_rate = {r[0], r[1], r[2]};
    }
    if (rotation) {
        rotation->eval(t, v, want);
        trs.rotate = quatAt(v);
        rotate_rate = quatAt(r);
    }
    if (scale) {
        scale->eval(t, v, want);
        trs.scale = {v[0], v[1], v[2]};
        scale_rate = {r[0], r[1], r[2]};
    }
    if (rate) {
        // d/dt T R S: the translation's rate in the last column, R' S + R S' in the linear part, where
        // R' = [omega]x R with omega = 2 vec(q' q*) for a unit q.
        const glm::dquat w = 2.0 * (rotate_rate * glm::conjugate(trs.rotate));
        const glm::dmat3 cross(glm::dvec3(0.0, w.z, -w.y), glm::dvec3(-w.z, 0.0, w.x), glm::dvec3(w.y, -w.x, 0.0));
        const glm::dmat3 r3 = glm::mat3_cast(trs.rotate);
        const glm::dmat3 linear = cross * r3 * glm::dmat3(glm::scale(glm::dmat4(1.0), trs.scale)) +
                                  r3 * glm::dmat3(glm::scale(glm::dmat4(1.0), scale_rate));
        *rate = glm::dmat4(linear);
        (*rate)[3] = glm::dvec4(translate_rate, 0.0);
    }
    return trsMatrix(trs);
}

glm::dmat4 ChainMotion::product(double t, glm::dmat4* rate) const {
    glm::dmat4 m(1.0);
    glm::dmat4 d(0.0);
    for (const AnimatedNode* node : chain) {
        glm::dmat4 local_rate;
        const glm::dmat4 l = node->local(t, rate ? &local_rate : nullptr);
        if (rate) d = d * l + m * local_rate;
        m = m * l;
    }
    if (rate) *rate = d * tail;
    return m * tail;
}

glm::dmat4 ChainMotion::world(double t) const {
    const glm::dmat4 m = product(t, nullptr);
    if (!rigid) return m;
    const glm::dvec3 back = glm::normalize(glm::dvec3(m[2]));
    const glm::dvec3 y = glm::dvec3(m[1]);
    const glm::dvec3 up = glm::normalize(y - glm::dot(y, back) * back);
    return glm::dmat4(glm::dvec4(glm::cross(up, back), 0.0), glm::dvec4(up, 0.0), glm::dvec4(back, 0.0), m[3]);
}

RigidTransform decomposeMatrix(const glm::dmat4& m) {
    glm::dvec3 axes[3] = {glm::dvec3(m[0]), glm::dvec3(m[1]), glm::dvec3(m[2])};
    RigidTransform out;
    out.translate = glm::dvec3(m[3]);
    for (int i = 0; i < 3; ++i) {
        out.scale[i] = glm::length(axes[i]);
        if (!(out.scale[i] > 0.0) || !std::isfinite(out.scale[i])) throw std::domain_error("a zero or infinite scale");
        axes[i] /= out.scale[i];
    }
    // 1e-9: rounding in products of a few float-sourced matrices stays far below it; real shear does not.
    for (int i = 0; i < 3; ++i)
        if (std::abs(glm::dot(axes[i], axes[(i + 1) % 3])) > 1e-9)
            throw std::domain_error("shear (a non-uniform scale under a rotation)");
    if (glm::dot(glm::cross(axes[0], axes[1]), axes[2]) < 0.0) {
        out.scale.x = -out.scale.x;
        axes[0] = -axes[0];
    }
    out.rotate = glm::normalize(glm::quat_cast(glm::dmat3(axes[0], axes[1], axes[2])));
    return out;
}

namespace {

void addTrackTimes(const Track* track, std::vector<double>& times, std::vector<double>& steps) {
    if (!track) return;
    times.insert(times.end(), track->times.begin(), track->times.end());
    if (track->interpolation == Interpolation::Step)
        steps.insert(steps.end(), track->times.begin() + 1, track->times.end());
}

bool uniformScale(const glm::dmat4& m) {
    try {
        const RigidTransform r = decomposeMatrix(m);
        const double s = r.scale.x;
        return s > 0.0 && std::abs(r.scale.y - s) <= 1e-12 * s && std::abs(r.scale.z - s) <= 1e-12 * s;
    } catch (const std::domain_error&) {
        return false;
    }
}

}  // namespace

KeyPlan planTimes(const std::vector<const Track*>& tracks) {
    std::vector<double> times;
    std::vector<double> steps;
    for (const Track* track : tracks) addTrackTimes(track, times, steps);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    std::sort(steps.begin(), steps.end());
    steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
    // A STEP key holds its value until the next key: one more key a short window before each jump.
    std::vector<double> holds;
    for (const double s : steps) {
        const auto at = std::lower_bound(times.begin(), times.end(), s);
        const double previous = at == times.begin() ? s - 2 * kStepWindowFrames : *(at - 1);
        holds.push_back(s - std::min(kStepWindowFrames, 0.5 * (s - previous)));
    }
    times.insert(times.end(), holds.begin(), holds.end());
    std::sort(times.begin(), times.end());
    KeyPlan plan;
    plan.times = times;
    plan.jump_after.assign(times.size(), false);
    for (std::size_t i = 0; i + 1 < times.size(); ++i)
        plan.jump_after[i] = std::binary_search(steps.begin(), steps.end(), times[i + 1]) &&
                             std::binary_search(holds.begin(), holds.end(), times[i]);
    return plan;
}

KeyPlan planKeys(const ChainMotion& motion) {
    std::vector<const Track*> tracks;
    std::size_t animated = 0;
    bool cubic = false;
    for (const AnimatedNode* node : motion.chain) {
        if (!node->animated()) continue;
        ++animated;
        for (const Track* t : {node->translation, node->rotation, node->scale}) {
            if (!t) continue;
            tracks.push_back(t);
            cubic = cubic || t->interpolation == Interpolation::CubicSpline;
        }
    }
    KeyPlan plan = planTimes(tracks);
    glm::dmat4 parent(1.0);
    for (std::size_t i = 0; i + 1 < motion.chain.size(); ++i) parent = parent * motion.chain[i]->local(0.0);
    plan.exact = animated == 1 && motion.chain.back()->animated() && !cubic && uniformScale(parent) &&
                 motion.tail == glm::dmat4(1.0);
    return plan;
}

namespace {

TransformKey keyAt(const ChainMotion& motion, double t) {
    const RigidTransform r = decomposeMatrix(motion.world(t));
    return TransformKey{t, r.translate, r.rotate, r.scale};
}

double deviation(const ChainMotion& motion, const TransformKey& a, const TransformKey& b, double t,
                 const std::vector<glm::dvec3>& corners) {
    const RigidTransform keyed = evalTransform({a, b}, t);
    const glm::dmat4 exact = motion.world(t);
    double worst = 0.0;
    for (const glm::dvec3& c : corners)
        worst = std::max(worst, glm::length(keyed.apply(c) - glm::dvec3(exact * glm::dvec4(c, 1.0))));
    return worst;
}

// Appends keys strictly inside (a, b) and then b, bisecting where the keys stray beyond the tolerance.
struct Refinement {
    const ChainMotion& motion;
    const ResampleSpec& spec;
    std::vector<TransformKey>& out;

    void run(const TransformKey& a, const TransformKey& b, int depth) {
        bool fine = true;
        if (depth < 40)
            for (const double q : {0.25, 0.5, 0.75})
                if (deviation(motion, a, b, a.time + q * (b.time - a.time), spec.corners) > spec.tolerance) fine = false;
        if (!fine) {
            const TransformKey mid = keyAt(motion, 0.5 * (a.time + b.time));
            run(a, mid, depth + 1);
            run(mid, b, depth + 1);
            return;
        }
        out.push_back(b);
        if (out.size() > spec.max_keys) throw std::length_error("too many keys");
    }
};

}  // namespace

std::vector<TransformKey> followChain(const ChainMotion& motion, const KeyPlan& plan, const ResampleSpec& spec) {
    std::vector<TransformKey> keys;
    if (plan.times.empty()) return keys;
    keys.push_back(keyAt(motion, plan.times.front()));
    for (std::size_t i = 0; i + 1 < plan.times.size(); ++i) {
        const TransformKey next = keyAt(motion, plan.times[i + 1]);
        if (plan.exact || plan.jump_after[i]) {
            keys.push_back(next);
            if (keys.size() > spec.max_keys) throw std::length_error("too many keys");
        } else {
            const TransformKey start = keys.back();
            Refinement{motion, spec, keys}.run(start, next, 0);
        }
    }
    return keys;
}

}  // namespace clipblur
