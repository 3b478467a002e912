#include "renderer/clipped/shutter_segments.h"

#include <algorithm>
#include <cmath>
#include <numbers>


namespace clipblur {

namespace {

// How many parts of `per_part` degrees `radians` needs (1e-9: a turn of exactly n parts is n).
int partsOf(double radians, double per_part) {
    return static_cast<int>(std::ceil(radians * 180.0 / std::numbers::pi / per_part - 1e-9));
}

}  // namespace

int shutterSegments(const FrameMotion& motion, int requested, int max_segments) {
    if (requested > 0) return std::min(requested, max_segments);
    const FrameMotion::Turns turns = motion.turns(motion.t0(), motion.t1());
    const int n = std::max(partsOf(turns.camera, kAutoSegmentTurnDegrees), partsOf(turns.objects, kAutoSegmentObjectTurnDegrees));
    return std::clamp(n, 1, max_segments);
}

std::vector<ShutterSegment> equalSegments(double t0, double t1, int count) {
    std::vector<ShutterSegment> segments;
    double begin = t0;
    for (int s = 1; s <= count; ++s) {
        const double end = t0 + (t1 - t0) * s / count;  // as every segment's times have always been
        segments.push_back({begin, end, 1.0 / count, 1.0, 1.0});
        begin = end;
    }
    return segments;
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
