#include "renderer/clipped/shutter_segments.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/gtc/quaternion.hpp>

#include "scene/camera.h"
#include "scene/object_motion.h"

namespace clipblur {

namespace {

double angleBetween(const glm::dquat& a, const glm::dquat& b) {
    const double c = std::min(1.0, std::abs(glm::dot(glm::normalize(a), glm::normalize(b))));
    return 2.0 * std::acos(c);
}

}  // namespace

double largestTurn(const Scene& scene, double t0, double t1) {
    // Slerp and the camera's SO(3) interpolation turn at a constant rate within a key interval, and keys
    // turn by less than pi each; 256 samples resolve any shutter with fewer than 128 keys inside it.
    constexpr int kSamples = 256;
    const auto turn = [&](auto orientation) {
        double total = 0.0;
        glm::dquat previous = orientation(t0);
        for (int i = 1; i <= kSamples; ++i) {
            const glm::dquat q = orientation(t0 + (t1 - t0) * i / kSamples);
            total += angleBetween(previous, q);
            previous = q;
        }
        return total;
    };
    double largest = turn([&](double t) { return glm::quat_cast(evalCamera(scene.camera, t).basis()); });
    for (const Object& object : scene.objects) {
        if (object.transform.size() < 2) continue;
        largest = std::max(largest, turn([&](double t) { return evalTransform(object.transform, t).rotate; }));
    }
    return largest;
}

bool sceneIsStill(const Scene& scene, double t0, double t1) {
    const auto same = [](const CameraFrame& a, const CameraFrame& b) {
        return a.position == b.position && a.e1 == b.e1 && a.e2 == b.e2 && a.e3 == b.e3;
    };
    if (!cameraKeeps(scene.camera, t0, t1, same)) return false;
    for (const Object& object : scene.objects)
        if (!isStatic(object, t0, t1)) return false;
    return true;
}

int shutterSegments(const Scene& scene, double t0, double t1, int requested, int max_segments) {
    if (requested > 0) return std::min(requested, max_segments);
    const double degrees = largestTurn(scene, t0, t1) * 180.0 / std::numbers::pi;
    const int n = static_cast<int>(std::ceil(degrees / kAutoSegmentTurnDegrees - 1e-9));
    return std::clamp(n, 1, max_segments);
}

std::vector<ShutterSegment> equalSegments(double t0, double t1, int count) {
    std::vector<ShutterSegment> segments;
    double begin = t0;
    for (int s = 1; s <= count; ++s) {
        const double end = t0 + (t1 - t0) * s / count;  // as every segment's times have always been
        segments.push_back({begin, end, 1.0 / count});
        begin = end;
    }
    return segments;
}

std::vector<ShutterSegment> splitWhereHidden(const std::vector<ShutterSegment>& segments, int max_segments,
                                             const std::function<bool(double, double)>& hidden, int& unsplit) {
    unsplit = 0;
    int count = static_cast<int>(segments.size());
    std::vector<ShutterSegment> out;
    std::vector<ShutterSegment> pending(segments.rbegin(), segments.rend());  // the next one last
    while (!pending.empty()) {
        const ShutterSegment s = pending.back();
        pending.pop_back();
        if (hidden(s.begin, s.end)) {
            if (count < max_segments) {
                const double middle = 0.5 * (s.begin + s.end);
                pending.push_back({middle, s.end, 0.5 * s.weight});
                pending.push_back({s.begin, middle, 0.5 * s.weight});
                ++count;
                continue;
            }
            ++unsplit;
        }
        out.push_back(s);
    }
    return out;
}

std::vector<ShutterSegment> splitAtCurve(const std::vector<ShutterSegment>& segments, const ShutterCurve& curve) {
    if (curve.box()) return segments;
    std::vector<ShutterSegment> out;
    const auto piece = [&](double begin, double end) {
        const ShutterSegment s{begin, end, curve.mass(begin, end), curve.weightAt(begin), curve.weightAt(end)};
        if (s.curve_begin > 0.0 || s.curve_end > 0.0) out.push_back(s);
    };
    for (const ShutterSegment& s : segments) {
        double begin = s.begin;
        for (const double t : curve.times()) {
            if (t <= s.begin || t >= s.end) continue;
            piece(begin, t);
            begin = t;
        }
        piece(begin, s.end);
    }
    return out;
}

}  // namespace clipblur
