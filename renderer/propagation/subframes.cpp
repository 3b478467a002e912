#include "renderer/propagation/subframes.h"

#include "renderer/geometry/predicates.h"
#include "renderer/geometry/swept_footprint.h"
#include "renderer/thread_scratch.h"

#include <algorithm>
#include <atomic>
#include <array>
#include <cmath>
#include <optional>

namespace clipblur {

namespace {

void addKeyTimes(std::vector<double>& times, double t0, double t1, const auto& keys) {
    for (const auto& key : keys)
        if (key.time > t0 && key.time < t1) times.push_back(key.time);
}

// J, the affine map with J (b - a) = (b' - a') and J (c - a) = (c' - a'), for a triangle a b c no thinner
// than `thinness` (det / (|e1|^2 + |e2|^2), 0.5 for a right isosceles one).
std::optional<glm::dmat2> openToClose(const std::array<glm::dvec2, 3>& open, const std::array<glm::dvec2, 3>& close,
                                      double thinness) {
    const glm::dvec2 e1 = open[1] - open[0], e2 = open[2] - open[0];
    const double det = e1.x * e2.y - e1.y * e2.x;
    if (!(std::abs(det) > thinness * (glm::dot(e1, e1) + glm::dot(e2, e2)))) return std::nullopt;
    return glm::dmat2(close[1] - close[0], close[2] - close[0]) * glm::inverse(glm::dmat2(e1, e2));
}

// A sliver's J says little: where motion is not affine (a camera turn is a homography), the part of the
// displacement that bends along its length is divided by its width. Triangles thinner than about 1:10
// are left out. A fragment is placed at its interval's middle and turns by half the interval's residual
// to either end; its vertices lie within half an edge of its centre, and within half a pixel's diagonal
// for a piece of one pixel: hence |(J - S) e| / |e| x min(|e|, sqrt 2) / 4 with one interval.
void affineMotion(const std::array<glm::dvec2, 3>& open, const std::array<glm::dvec2, 3>& close, FragmentMotion& out) {
    const std::optional<glm::dmat2> map = openToClose(open, close, 0.05);
    if (!map) return;
    const glm::dmat2& j = *map;
    const glm::dvec2 e1 = open[1] - open[0], e2 = open[2] - open[0];
    // S as the sweep stretches (signedStretch).
    const glm::dmat2 residual = j - glm::dmat2(signedStretch(j, 0), 0.0, 0.0, signedStretch(j, 1));
    for (const glm::dvec2& e : {e1, e2, open[2] - open[1]}) {
        const double length = glm::length(e);
        if (length > 0.0)
            out.unstretched_error =
                std::max(out.unstretched_error, glm::length(residual * e) / length * std::min(length, std::sqrt(2.0)) / 4.0);
    }
}

// A thread's corners of the mesh triangle it last measured, at every node of one sampler and then at
// mid-shutter: fragments of one triangle mostly follow each other in a fragment set, and a fragment
// vertex's camera-relative position and rate are its barycentric combination of its triangle's corners'.
struct TriangleCorners {
    std::uint64_t sampler = 0;  // ShutterPathSampler::id_ of the sampler that filled it; 0: none
    std::uint32_t object = 0, triangle = 0;
    bool filled = false;  // `at` holds this triangle's corners
    std::vector<std::array<CameraRelative, 3>> at;
};

CameraRelative combine(const std::array<CameraRelative, 3>& c, const glm::dvec3& b) {
    return {b[0] * c[0].d + b[1] * c[1].d + b[2] * c[2].d, b[0] * c[0].g + b[1] * c[1].g + b[2] * c[2].g};
}

std::atomic<std::uint64_t> next_sampler_id{1};

}  // namespace

const std::vector<std::array<CameraRelative, 3>>* ShutterPathSampler::cornersOf(const MeshPoint& point) const {
    TriangleCorners& c = threadScratch<TriangleCorners>();
    if (c.sampler != id_ || c.object != point.object || c.triangle != point.triangle) {
        // A triangle's first fragment in a run is projected vertex by vertex: where each triangle has
        // one fragment (a dense mesh), filling its corners would cost more than it saves.
        c.sampler = id_;
        c.object = point.object;
        c.triangle = point.triangle;
        c.filled = false;
        return nullptr;
    }
    if (!c.filled) {
        c.at.resize(nodes_.size() + 1);
        for (std::size_t i = 0; i < c.at.size(); ++i)
            for (int j = 0; j < 3; ++j) {
                MeshPoint corner{point.object, point.triangle, glm::dvec3(0.0)};
                corner.b[j] = 1.0;
                c.at[i][static_cast<std::size_t>(j)] = cameraRelative(i < nodes_.size() ? nodes_[i].snapshot : middle_, *scene_, corner);
            }
        c.filled = true;
    }
    return &c.at;
}

ShutterPathSampler::ShutterPathSampler(const Scene& scene, const Projection& projection, double t0, double t1,
                                       int intervals_per_piece)
    : scene_(&scene), middle_(scene, projection, 0.5 * (t0 + t1)), duration_(std::max(0.0, t1 - t0)),
      id_(next_sampler_id++) {
    breakpoints_.push_back(t0);
    addKeyTimes(breakpoints_, t0, t1, scene.camera.keys);
    for (const Object& object : scene.objects) addMotionKeyTimes(object, t0, t1, breakpoints_);
    std::sort(breakpoints_.begin(), breakpoints_.end());
    breakpoints_.erase(std::unique(breakpoints_.begin(), breakpoints_.end()), breakpoints_.end());
    if (t1 > t0) breakpoints_.push_back(t1);

    // 3-point Gauss-Legendre on [-1, 1]: exact for quintics, so |velocity| of smooth paths converges fast.
    const double gl_x = std::sqrt(0.6);
    const double gl_nodes[3] = {-gl_x, 0.0, gl_x};
    const double gl_weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    const int intervals = std::max(1, intervals_per_piece);
    auto add = [&](double t, double weight) { nodes_.push_back({MotionSnapshot(scene, projection, t), weight}); };
    for (std::size_t p = 0; p + 1 < breakpoints_.size(); ++p) {
        const double a = breakpoints_[p];
        const double h = (breakpoints_[p + 1] - a) / intervals;
        for (int i = 0; i < intervals; ++i) {
            const double u = a + i * h;
            add(u, 0.0);
            for (int g = 0; g < 3; ++g) add(u + 0.5 * h * (1.0 + gl_nodes[g]), 0.5 * h * gl_weights[g]);
        }
    }
    add(breakpoints_.back(), 0.0);
    for (std::size_t i = 1; i < nodes_.size(); ++i)
        max_gap_ = std::max(max_gap_, nodes_[i].snapshot.time - nodes_[i - 1].snapshot.time);
    std::vector<double> times;
    for (const Node& node : nodes_) times.push_back(node.snapshot.time);
    turns_ = cameraTurns(scene, projection, middle_.time, times);
    if (!turns_.empty()) {
        unturn_open_ = glm::inverse(turns_.front());
        unturn_close_ = glm::inverse(turns_.back());
    }
    straight_.assign(scene.objects.size(), 0);
    if (breakpoints_.size() != 2 || !turns_.empty() || scene.camera.motion) return;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        if (object.motion || deformsOver(object, t0, t1)) continue;
        const RigidTransform a = evalTransform(object.transform, t0), b = evalTransform(object.transform, t1);
        straight_[o] = a.rotate == b.rotate && a.scale == b.scale ? 1 : 0;
    }
}

bool ShutterPathSampler::measureStraight(std::span<const MeshPoint> vertices, FragmentMotion& out) const {
    const MotionSnapshot& open = nodes_.front().snapshot;
    const MotionSnapshot& close = nodes_.back().snapshot;
    std::array<glm::dvec2, 3> o{}, c{};
    double max_speed = 0.0;
    for (std::size_t k = 0; k < vertices.size(); ++k) {
        const ProjectedPoint a = project(open, *scene_, vertices[k]), b = project(close, *scene_, vertices[k]);
        if (a.behind || b.behind) return false;
        out.swept.expand(a.raster);
        out.swept.expand(b.raster);
        out.min_depth = std::min({out.min_depth, a.depth, b.depth});
        out.max_depth = std::max({out.max_depth, a.depth, b.depth});
        // raster - centre = (A + B t) / z(t) with z linear: the velocity (B z0 - A z') / z^2 keeps its
        // direction, and integrating it over the shutter gives the chord (B z0 - A z') T / (z_a z_b). So
        // the path is its chord, and its speed, largest at the nearer end, is |chord| / T x z_far / z_near.
        const double chord = glm::length(b.raster - a.raster);
        out.max_path_pixels = std::max(out.max_path_pixels, chord);
        max_speed = std::max(max_speed, chord / duration_ * std::max(a.depth / b.depth, b.depth / a.depth));
        if (k < 3) {
            o[k] = a.raster;
            c[k] = b.raster;
        }
        out.start += a.raster / double(vertices.size());
        out.end += b.raster / double(vertices.size());
    }
    out.max_sweep_pixels = std::max(out.max_path_pixels, max_speed * duration_);
    // The sweep's path is the homogeneous parabola through the positions at open, middle and close: for
    // homogeneous coordinates linear in time, that line itself.
    out.parabola_deviation = 0.0;
    if (vertices.size() == 3) {
        affineMotion(o, c, out);
        sourceMap(vertices[0], out);
    }
    return true;
}

double ShutterPathSampler::pathLength(const MeshPoint& point) const {
    double length = 0.0;
    for (const Node& node : nodes_) {
        if (node.weight == 0.0) continue;
        const ProjectedMotion m = projectMotion(node.snapshot, *scene_, point);
        if (!m.point.behind) length += node.weight * glm::length(m.raster_velocity);
    }
    return length;
}

FragmentMotion ShutterPathSampler::measure(std::span<const MeshPoint> vertices) const {
    FragmentMotion out;
    if (!vertices.empty() && std::all_of(vertices.begin(), vertices.end(), [&](const MeshPoint& v) { return straight(v.object); })) {
        if (measureStraight(vertices, out)) return out;
        out = FragmentMotion{};
    }
    double max_speed = 0.0, max_depth_rate = 0.0;
    struct Positions {
        std::vector<glm::dvec3> raster;  // raster x, y and depth
    };
    std::vector<glm::dvec3>& positions = threadScratch<Positions>().raster;
    std::array<glm::dvec2, 3> open{}, close{};
    std::size_t ends = 0;  // vertices with both end positions
    const bool one_triangle = std::all_of(vertices.begin(), vertices.end(), [&](const MeshPoint& v) {
        return v.object == vertices[0].object && v.triangle == vertices[0].triangle;
    });
    const std::vector<std::array<CameraRelative, 3>>* corners = one_triangle && !vertices.empty() ? cornersOf(vertices[0]) : nullptr;
    // Node i's projection of a vertex (i == nodes_.size(): mid-shutter).
    const auto motionAt = [&](std::size_t i, const MeshPoint& vertex) {
        const MotionSnapshot& at = i < nodes_.size() ? nodes_[i].snapshot : middle_;
        return corners ? projectMotion(at, combine((*corners)[i], vertex.b)) : projectMotion(at, *scene_, vertex);
    };
    for (const MeshPoint& vertex : vertices) {
        double length = 0.0;
        positions.clear();
        for (std::size_t i = 0; i < nodes_.size(); ++i) {
            const Node& node = nodes_[i];
            const ProjectedMotion m = motionAt(i, vertex);
            if (m.point.behind) {
                out.crosses_near = true;
                continue;
            }
            positions.push_back(glm::dvec3(m.point.raster, m.point.depth));
            out.swept.expand(m.point.raster);
            out.min_depth = std::min(out.min_depth, m.point.depth);
            out.max_depth = std::max(out.max_depth, m.point.depth);
            max_depth_rate = std::max(max_depth_rate, std::abs(m.depth_rate));
            if (node.weight == 0.0) continue;
            const double speed = glm::length(m.raster_velocity);
            length += node.weight * speed;
            max_speed = std::max(max_speed, speed);
        }
        out.max_path_pixels = std::max(out.max_path_pixels, length);
        if (positions.size() == nodes_.size() && duration_ > 0.0) {
            const glm::dvec2 a(positions.front()), b(positions.back());
            if (ends < 3) {
                open[ends] = a;
                close[ends] = b;
            }
            ++ends;
            out.start += a / double(vertices.size());
            out.end += b / double(vertices.size());
            const ProjectedPoint mid = motionAt(nodes_.size(), vertex).point;
            if (!mid.behind) out.parabola_deviation = std::max(out.parabola_deviation, parabolaDeviation(positions, mid));
        }
    }
    out.max_sweep_pixels = std::max(out.max_path_pixels, max_speed * duration_);
    if (ends == 3 && vertices.size() == 3) {
        affineMotion(open, close, out);
        sourceMap(vertices[0], out, corners);
    }
    if (out.crosses_near) {
        out.swept = RasterBounds::everything();
    } else {
        out.swept.pad(max_speed * max_gap_);
        out.min_depth -= max_depth_rate * max_gap_;
        out.max_depth += max_depth_rate * max_gap_;
    }
    return out;
}

double ShutterPathSampler::parabolaDeviation(const std::vector<glm::dvec3>& positions, const ProjectedPoint& mid) const {
    // What a one-interval sweep follows (SweepPath: the homogeneous parabola through the positions and
    // depths at open, mid-shutter and close, with the camera's turn taken out and put back), at u = s + 1/2.
    const glm::dvec2 a(positions.front()), b(positions.back());
    const SweepPath path = SweepPath::through({a, positions.front().z}, {mid.raster, mid.depth}, {b, positions.back().z},
                                              unturn_open_, unturn_close_);
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    double deviation = turns_.empty() && !std::isfinite(path.reach()) ? kInfinity : 0.0;
    const double t0 = nodes_.front().snapshot.time;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        const double s = (nodes_[i].snapshot.time - t0) / duration_ - 0.5;
        glm::dvec2 offset, stretch;
        path.place(s, turns_.empty() ? nullptr : &turns_[i], offset, stretch);
        const double miss = glm::length(glm::dvec2(positions[i]) - (mid.raster + offset));
        deviation = std::max(deviation, std::isfinite(miss) ? miss : kInfinity);
    }
    return deviation;
}

void ShutterPathSampler::sourceMap(const MeshPoint& point, FragmentMotion& out,
                                   const std::vector<std::array<CameraRelative, 3>>* corners) const {
    std::array<glm::dvec2, 3> open{}, close{};
    std::array<double, 3> inv_depth{};
    for (int i = 0; i < 3; ++i) {
        MeshPoint corner = point;
        corner.b = glm::dvec3(0.0);
        corner.b[i] = 1.0;
        const auto at = [&](std::size_t node) {
            const MotionSnapshot& s = nodes_[node].snapshot;
            return corners ? projectMotion(s, (*corners)[node][static_cast<std::size_t>(i)]).point : project(s, *scene_, corner);
        };
        const ProjectedPoint a = at(0), b = at(nodes_.size() - 1);
        if (a.behind || b.behind) return;
        open[static_cast<std::size_t>(i)] = a.raster;
        inv_depth[static_cast<std::size_t>(i)] = a.inv_depth;
        close[static_cast<std::size_t>(i)] = b.raster;
    }
    // A face seen edge-on has no map across it; one nearly edge-on still has an exact one for motion
    // that is affine in the image (a turn about the view axis), and its pieces are too thin to matter
    // where it is not.
    const std::optional<glm::dmat2> map = openToClose(open, close, 1e-3);
    if (!map) return;
    out.open_to_close = *map;
    out.source_open = open;
    out.source_open_inv_depth = inv_depth;
    out.has_source = true;
}

std::optional<double> FragmentMotion::inverseDepthAt(const glm::dvec2& x) const {
    const auto& [a, b, c] = source_open;
    // Barycentric weights by sub-triangle areas; the triangle is not edge-on (openToClose accepted it).
    const double area = differenceOfProducts(b.x - a.x, c.y - a.y, b.y - a.y, c.x - a.x);
    const double wb = differenceOfProducts(x.x - a.x, c.y - a.y, x.y - a.y, c.x - a.x) / area;
    const double wc = differenceOfProducts(b.x - a.x, x.y - a.y, b.y - a.y, x.x - a.x) / area;
    const double wa = 1.0 - wb - wc;
    if (wa < 0.0 || wb < 0.0 || wc < 0.0) return std::nullopt;
    return wa * source_open_inv_depth[0] + wb * source_open_inv_depth[1] + wc * source_open_inv_depth[2];
}

int subframeCount(double pixels, int max_subframes, bool* capped) {
    const int limit = std::max(1, max_subframes);
    // A millionth of a pixel of slack so a path of exactly n pixels, computed with rounding, gives n.
    const double wanted = std::ceil(pixels - 1e-6);
    const bool over = !(wanted <= static_cast<double>(limit));  // also catches NaN and infinity
    if (capped) *capped = over;
    if (over) return limit;
    return std::max(1, static_cast<int>(wanted));
}

SubframePlan planSubframes(std::span<const FragmentMotion> fragments, const RasterBounds& tile, int max_subframes) {
    SubframePlan plan;
    for (const FragmentMotion& fragment : fragments) {
        if (!fragment.swept.overlaps(tile)) continue;
        ++plan.fragments;
        if (fragment.crosses_near) ++plan.near_crossings;
        plan.max_path_pixels = std::max(plan.max_path_pixels, fragment.max_path_pixels);
        plan.max_sweep_pixels = std::max(plan.max_sweep_pixels, fragment.max_sweep_pixels);
    }
    plan.count = subframeCount(plan.max_sweep_pixels, max_subframes, &plan.capped);
    return plan;
}

std::vector<double> subframeTimes(double t0, double t1, int count) {
    std::vector<double> times(static_cast<std::size_t>(std::max(1, count)));
    const double n = static_cast<double>(times.size());
    for (std::size_t k = 0; k < times.size(); ++k) times[k] = t0 + (static_cast<double>(k) + 0.5) / n * (t1 - t0);
    return times;
}

}  // namespace clipblur
