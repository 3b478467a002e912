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

// The u in [0, 1] for which the box (1 - u) a + u b meets `c`, as [u0, u1]; none when it never does. Per
// axis its low side must stay under c's high side and its high side over c's low side, each a bound on u.
std::optional<std::pair<double, double>> blendMeets(const RasterBounds& a, const RasterBounds& b, const RasterBounds& c) {
    if (a.empty() || b.empty()) return std::nullopt;
    double u0 = 0.0, u1 = 1.0;
    const auto atMost = [&](double v0, double v1, double limit) {  // v0 + u (v1 - v0) <= limit
        if (v1 == v0) {
            if (v0 > limit) u0 = 2.0;
        } else if (v1 > v0) {
            u1 = std::min(u1, (limit - v0) / (v1 - v0));
        } else {
            u0 = std::max(u0, (limit - v0) / (v1 - v0));
        }
    };
    for (int axis = 0; axis < 2; ++axis) {
        atMost(a.lo[axis], b.lo[axis], c.hi[axis]);
        atMost(-a.hi[axis], -b.hi[axis], -c.lo[axis]);
    }
    if (u0 > u1) return std::nullopt;
    return std::pair(u0, u1);
}

RasterBounds pointBox(const glm::dvec2& p) { return {p, p}; }

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
      film_{{0.0, 0.0}, {double(projection.width), double(projection.height)}}, id_(next_sampler_id++) {
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
    RasterBounds at_open, at_close;
    double max_speed = 0.0, all_speed = 0.0, all_path = 0.0;
    bool seen = false;  // a vertex is on the image
    for (std::size_t k = 0; k < vertices.size(); ++k) {
        const ProjectedPoint a = project(open, *scene_, vertices[k]), b = project(close, *scene_, vertices[k]);
        if (a.behind || b.behind) return false;
        at_open.expand(a.raster);
        at_close.expand(b.raster);
        out.min_depth = std::min({out.min_depth, a.depth, b.depth});
        out.max_depth = std::max({out.max_depth, a.depth, b.depth});
        // raster - centre = (A + B t) / z(t) with z linear: the velocity (B z0 - A z') / z^2 keeps its
        // direction, and integrating it over the shutter gives the chord (B z0 - A z') T / (z_a z_b). So
        // the path is its chord, and its speed |chord| / T x z_a z_b / z^2; 1/z is affine in the distance
        // u along the chord, so the square root of the speed is too. Only the part of the chord on the
        // image counts (measure), and the speed is largest at that part's nearer end.
        const double chord = glm::length(b.raster - a.raster);
        const double root_a = std::sqrt(chord / duration_ * b.depth / a.depth), root_b = std::sqrt(chord / duration_ * a.depth / b.depth);
        all_path = std::max(all_path, chord);
        all_speed = std::max({all_speed, root_a * root_a, root_b * root_b});
        if (const auto range = blendMeets(pointBox(a.raster), pointBox(b.raster), film_)) {
            const auto [u0, u1] = *range;
            out.max_path_pixels = std::max(out.max_path_pixels, chord * (u1 - u0));
            for (const double u : {u0, u1}) max_speed = std::max(max_speed, std::pow((1.0 - u) * root_a + u * root_b, 2.0));
            seen = true;
        }
        if (k < 3) {
            o[k] = a.raster;
            c[k] = b.raster;
        }
        out.start += a.raster / double(vertices.size());
        out.end += b.raster / double(vertices.size());
    }
    // The fragment is within the hull of its ends' boxes. One no vertex of which is on the image but that
    // may span it on the way (its box about the blend of its boxes at the ends) counts whole.
    out.swept = at_open;
    out.swept.expand(at_close.lo);
    out.swept.expand(at_close.hi);
    if (!seen && blendMeets(at_open, at_close, film_)) {
        out.max_path_pixels = all_path;
        max_speed = all_speed;
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

// On straight paths every point of the fragment at any time lies in the convex hull of its vertices'
// camera-relative positions at open and close (each moves linearly; the camera does not turn). The part
// of that hull at or beyond the near depth, all that a re-clip can draw (it cuts at a depth no nearer),
// is a polytope whose corners are those positions beyond it and the points where the segments between
// two of them cross it; a perspective projection maps it onto the hull of its corners' images.
RasterBounds ShutterPathSampler::crossingBounds(std::span<const MeshPoint> vertices) const {
    const MotionSnapshot& open = nodes_.front().snapshot;
    const MotionSnapshot& close = nodes_.back().snapshot;
    const CameraFrame& camera = open.camera;
    const double near = open.near_depth;
    std::vector<glm::dvec3>& d = threadScratch<std::vector<glm::dvec3>>();
    d.clear();
    for (const MeshPoint& v : vertices) {
        d.push_back(project(open, *scene_, v).world - open.camera.position);
        d.push_back(project(close, *scene_, v).world - close.camera.position);
    }
    RasterBounds box;
    const auto add = [&](const glm::dvec3& p, double depth) {
        box.expand(open.projection.toRaster(glm::dvec2(glm::dot(camera.e1, p), glm::dot(camera.e2, p)) / depth));
    };
    for (std::size_t i = 0; i < d.size(); ++i) {
        const double zi = glm::dot(camera.e3, d[i]);
        if (zi >= near) add(d[i], zi);
        for (std::size_t j = i + 1; j < d.size(); ++j) {
            const double zj = glm::dot(camera.e3, d[j]);
            if ((zi < near) != (zj < near)) add(d[i] + (near - zi) / (zj - zi) * (d[j] - d[i]), near);
        }
    }
    return box;
}

FragmentMotion ShutterPathSampler::measure(std::span<const MeshPoint> vertices) const {
    FragmentMotion out;
    const bool straight_paths =
        !vertices.empty() && std::all_of(vertices.begin(), vertices.end(), [&](const MeshPoint& v) { return straight(v.object); });
    if (straight_paths) {
        if (measureStraight(vertices, out)) return out;
        out = FragmentMotion{};
    }
    const std::size_t n = nodes_.size();
    struct Scratch {
        std::vector<ProjectedMotion> at;   // vertex-major: vertex k at node i is at[k * n + i]
        std::vector<glm::dvec3> raster;    // one vertex's raster x, y and depth, nodes in front of the camera
        std::vector<char> on_film;         // per node (onFilm)
    };
    Scratch& scratch = threadScratch<Scratch>();
    std::array<glm::dvec2, 3> open{}, close{};
    std::size_t ends = 0;  // vertices with both end positions
    const bool one_triangle = std::all_of(vertices.begin(), vertices.end(), [&](const MeshPoint& v) {
        return v.object == vertices[0].object && v.triangle == vertices[0].triangle;
    });
    const std::vector<std::array<CameraRelative, 3>>* corners = one_triangle && !vertices.empty() ? cornersOf(vertices[0]) : nullptr;
    // Node i's projection of a vertex (i == n: mid-shutter).
    const auto motionAt = [&](std::size_t i, const MeshPoint& vertex) {
        const MotionSnapshot& at = i < n ? nodes_[i].snapshot : middle_;
        return corners ? projectMotion(at, combine((*corners)[i], vertex.b)) : projectMotion(at, *scene_, vertex);
    };
    scratch.at.resize(vertices.size() * n);
    double max_depth_rate = 0.0;
    for (std::size_t k = 0; k < vertices.size(); ++k)
        for (std::size_t i = 0; i < n; ++i) {
            const ProjectedMotion& m = scratch.at[k * n + i] = motionAt(i, vertices[k]);
            if (m.point.behind) {
                out.crosses_near = true;
                continue;
            }
            out.min_depth = std::min(out.min_depth, m.point.depth);
            out.max_depth = std::max(out.max_depth, m.point.depth);
            max_depth_rate = std::max(max_depth_rate, std::abs(m.depth_rate));
        }
    // Off the image no pixel sees where a fragment is or how fast it goes: the swept box and the speeds
    // are of the nodes where it is on the image and of where it crosses the image's edge between them.
    const OnFilm film = onFilm(scratch.at, vertices.size(), scratch.on_film);
    double film_speed = film.edge_speed;
    out.swept = film.swept;
    for (std::size_t k = 0; k < vertices.size(); ++k) {
        double length = 0.0;
        scratch.raster.clear();
        for (std::size_t i = 0; i < n; ++i) {
            const ProjectedMotion& m = scratch.at[k * n + i];
            if (m.point.behind) continue;
            scratch.raster.push_back(glm::dvec3(m.point.raster, m.point.depth));
            if (!scratch.on_film[i] || nodes_[i].weight == 0.0) continue;
            const double speed = glm::length(m.raster_velocity);
            length += nodes_[i].weight * speed;
            film_speed = std::max(film_speed, speed);
        }
        out.max_path_pixels = std::max(out.max_path_pixels, length);
        if (scratch.raster.size() == n && duration_ > 0.0) {
            const glm::dvec2 a(scratch.raster.front()), b(scratch.raster.back());
            if (ends < 3) {
                open[ends] = a;
                close[ends] = b;
            }
            ++ends;
            out.start += a / double(vertices.size());
            out.end += b / double(vertices.size());
            const ProjectedPoint mid = motionAt(n, vertices[k]).point;
            if (!mid.behind)
                out.parabola_deviation = std::max(out.parabola_deviation, parabolaDeviation(scratch.raster, mid, scratch.on_film));
        }
    }
    out.max_sweep_pixels = std::max(out.max_path_pixels, film_speed * duration_);
    if (ends == 3 && vertices.size() == 3) {
        affineMotion(open, close, out);
        sourceMap(vertices[0], out, corners);
    }
    if (out.crosses_near) {
        out.swept = straight_paths ? crossingBounds(vertices) : RasterBounds::everything();
    } else {
        out.swept.pad(film_speed * max_gap_);
        out.min_depth -= max_depth_rate * max_gap_;
        out.max_depth += max_depth_rate * max_gap_;
    }
    return out;
}

ShutterPathSampler::OnFilm ShutterPathSampler::onFilm(const std::vector<ProjectedMotion>& at, std::size_t vertices,
                                                      std::vector<char>& on_film) const {
    const std::size_t n = nodes_.size();
    on_film.assign(n, 0);
    std::vector<RasterBounds>& box = threadScratch<std::vector<RasterBounds>>();
    box.assign(n, RasterBounds{});
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < vertices; ++k)
            if (!at[k * n + i].point.behind) box[i].expand(at[k * n + i].point.raster);
        on_film[i] = box[i].overlaps(film_) ? 1 : 0;
    }
    OnFilm out;
    bool crossed = false;  // a vertex crosses the image between nodes
    for (std::size_t i = 0; i + 1 < n; ++i) {
        bool touches = on_film[i] || on_film[i + 1];
        for (std::size_t k = 0; k < vertices; ++k) {
            const ProjectedMotion &a = at[k * n + i], &b = at[k * n + i + 1];
            if (a.point.behind || b.point.behind || (film_.contains(a.point.raster) && film_.contains(b.point.raster))) continue;
            // Between two nodes a vertex moves on a nearly straight line (exactly, for a camera and object
            // that do not turn); it is on the image for the part [u0, u1] of that line inside it. On such
            // a line inverse depth is affine in u, and speed goes as depth^-2: its square root is affine.
            const auto range = blendMeets(pointBox(a.point.raster), pointBox(b.point.raster), film_);
            if (!range) continue;
            touches = crossed = true;
            // At a key (and the shutter's ends) the velocity may belong to the next piece of motion: the
            // speeds are taken inside the pieces (measure), so there the other node's stands for it.
            const bool key_a = isBreakpoint(nodes_[i].snapshot.time), key_b = isBreakpoint(nodes_[i + 1].snapshot.time);
            const double sa = std::sqrt(glm::length(a.raster_velocity)), sb = std::sqrt(glm::length(b.raster_velocity));
            const double va = key_a ? sb : sa, vb = key_b ? sa : sb;
            for (const double u : {range->first, range->second})
                out.edge_speed = std::max(out.edge_speed, std::pow((1.0 - u) * va + u * vb, 2.0));
        }
        // A fragment no node or vertex shows on the image may still span it between two nodes (its box
        // there about the blend of its boxes at both).
        touches = touches || blendMeets(box[i], box[i + 1], film_).has_value();
        if (!touches || box[i].empty() || box[i + 1].empty()) continue;
        // Where it is on the image between the nodes: within both boxes' hull, and on the image.
        RasterBounds hull = box[i];
        hull.expand(box[i + 1].lo);
        hull.expand(box[i + 1].hi);
        out.swept.expand(glm::max(hull.lo, film_.lo));
        out.swept.expand(glm::min(hull.hi, film_.hi));
    }
    if (n == 1 && on_film[0]) {  // an instant: its box, on the image
        out.swept.expand(glm::max(box[0].lo, film_.lo));
        out.swept.expand(glm::min(box[0].hi, film_.hi));
    }
    // Seen only spanning the image: every node counts, as without this rule.
    if (!out.swept.empty() && !crossed && std::find(on_film.begin(), on_film.end(), 1) == on_film.end()) on_film.assign(n, 1);
    return out;
}

double ShutterPathSampler::parabolaDeviation(const std::vector<glm::dvec3>& positions, const ProjectedPoint& mid,
                                             const std::vector<char>& on_film) const {
    // What a one-interval sweep follows (SweepPath: the homogeneous parabola through the positions and
    // depths at open, mid-shutter and close, with the camera's turn taken out and put back), at u = s + 1/2.
    const glm::dvec2 a(positions.front()), b(positions.back());
    const SweepPath path = SweepPath::through({a, positions.front().z}, {mid.raster, mid.depth}, {b, positions.back().z},
                                              unturn_open_, unturn_close_);
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    const bool seen = std::find(on_film.begin(), on_film.end(), 1) != on_film.end();
    double deviation = seen && turns_.empty() && !std::isfinite(path.reach()) ? kInfinity : 0.0;
    const double t0 = nodes_.front().snapshot.time;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        if (!on_film[i]) continue;
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

double kinkSamples(double pixels, double share, double spacing) {
    // pixels first: a NaN stays NaN (std::max keeps its first argument unless the second is larger), and
    // subframeCount caps it.
    return std::max(pixels, std::sqrt(kKinkMotion * share * pixels)) / spacing;
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
