#include "scene/shutter_curve.h"

#include <algorithm>
#include <cmath>

namespace clipblur {

ShutterCurve::ShutterCurve(const Shutter& shutter, int frame) {
    const double base = static_cast<double>(frame);
    if (shutter.curve.empty()) {
        times_ = {base + shutter.open, base + shutter.close};
        weights_ = {1.0, 1.0};
    } else {
        for (const ShutterPoint& p : shutter.curve) {
            times_.push_back(base + p.time);
            weights_.push_back(p.weight);
        }
    }
    box_ = std::all_of(weights_.begin(), weights_.end(), [&](double w) { return w == weights_.front(); });
    cumulative_.push_back(0.0);
    for (std::size_t i = 0; i + 1 < times_.size(); ++i)
        cumulative_.push_back(cumulative_.back() + 0.5 * (weights_[i] + weights_[i + 1]) * (times_[i + 1] - times_[i]));
    total_ = cumulative_.back();
}

double ShutterCurve::weightAt(double t) const {
    if (!(t >= times_.front() && t <= times_.back())) return 0.0;
    if (t == times_.back()) return weights_.back();
    const std::size_t i = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()),
        times_.size() - 1);
    const std::size_t a = i - 1;
    const double length = times_[i] - times_[a];
    const double f = length > 0.0 ? (t - times_[a]) / length : 0.0;
    return weights_[a] + (weights_[i] - weights_[a]) * f;
}

double ShutterCurve::mass(double a, double b) const {
    if (!(total_ > 0.0)) return 0.0;  // a zero-length shutter: the renderers take the single instant
    // The integral from open to t: the full pieces before t and a trapezoid of the piece holding it.
    const auto upTo = [&](double t) {
        t = std::clamp(t, times_.front(), times_.back());
        std::size_t i = 0;
        while (i + 2 < times_.size() && times_[i + 1] <= t) ++i;
        return cumulative_[i] + 0.5 * (weights_[i] + weightAt(t)) * (t - times_[i]);
    };
    return (upTo(b) - upTo(a)) / total_;
}

double ShutterCurve::timeAt(double u) const {
    if (!(total_ > 0.0)) return times_.front();
    const double target = std::clamp(u, 0.0, 1.0) * total_;
    std::size_t i = 0;  // the last piece whose start lies below the target
    while (i + 2 < times_.size() && cumulative_[i + 1] < target) ++i;
    const double wa = weights_[i], wb = weights_[i + 1], length = times_[i + 1] - times_[i];
    const double m = target - cumulative_[i];
    // Within the piece, mass(tau) = wa tau + (wb - wa) tau^2 / (2 length) = m. The root in the form
    // 2m / (wa + sqrt(wa^2 + 2 (wb - wa) m / length)) has no cancellation and covers wa = wb and wa = 0.
    const double root = std::sqrt(std::max(0.0, wa * wa + 2.0 * (wb - wa) * m / length));
    const double denominator = wa + root;
    const double tau = denominator > 0.0 ? 2.0 * m / denominator : 0.0;
    return std::min(times_[i] + std::min(tau, length), times_[i + 1]);
}

}  // namespace clipblur
