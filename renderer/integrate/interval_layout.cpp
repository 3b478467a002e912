#include "renderer/integrate/interval_layout.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>

#include "renderer/parallel_time.h"

namespace clipblur {

IntervalTurns intervalTurns(const Scene& scene, const Projection& projection, double begin, double end, int positions) {
    const double middle = 0.5 * (begin + end);
    std::vector<double> times;
    for (int k = 0; k < positions; ++k) times.push_back(begin + (end - begin) * (k + 0.5) / positions);
    IntervalTurns out;
    out.at_positions = cameraTurns(scene, projection, middle, times);
    if (out.at_positions.empty()) return out;  // the positions see no turn (one position: the middle)
    const std::vector<glm::dmat3> ends = cameraTurns(scene, projection, middle, std::vector<double>{begin, end});
    if (!ends.empty()) {
        out.unturn_begin = glm::inverse(ends.front());
        out.unturn_end = glm::inverse(ends.back());
    }
    return out;
}

SweepInterval sweepInterval(const PixelBounds& tile, double max_sweep_pixels, int n, const PixelBounds& film) {
    SweepInterval s;
    s.reach = 2.0 * max_sweep_pixels / n + 1.0;
    const int apron = static_cast<int>(std::ceil(0.5 * s.reach)) + 1;
    s.resolve = tile;
    if (tile.x0 == 0) s.resolve.x0 -= apron;
    if (tile.y0 == 0) s.resolve.y0 -= apron;
    if (tile.x1 == film.x1) s.resolve.x1 += apron;
    if (tile.y1 == film.y1) s.resolve.y1 += apron;
    s.box = PixelBounds::corners(s.resolve.x0 - apron, s.resolve.y0 - apron, s.resolve.x1 + apron, s.resolve.y1 + apron);
    return s;
}

double bendLength(const glm::dvec2& a, const glm::dvec2& m, const glm::dvec2& b) {
    return std::sqrt(glm::length(m - 0.5 * (a + b)) / kBendTolerance);
}

std::vector<int> sweepPositions(const Scene& scene, const Projection& projection, const FragmentLayers& layers,
                                const SweepLayout& layout) {
    const double t0 = layout.t0, t1 = layout.t1;
    const int count = layout.intervals;
    // Both layers' fragment-triangle vertices, read in place: a copy as MeshPoints was 96 bytes a
    // fragment triangle (twice that while it grew), 72 MiB at 640x360 of dense_mesh.
    const std::size_t open_count = layers.triangles[0] ? layers.triangles[0]->size() : 0;
    const std::size_t close_count = layers.triangles[1] ? layers.triangles[1]->size() : 0;
    const std::size_t vertex_count = 3 * (open_count + close_count);
    const auto vertex = [&](std::size_t i) {
        const std::size_t t = i / 3;
        const FragmentTriangle& f = t < open_count ? (*layers.triangles[0])[t] : (*layers.triangles[1])[t - open_count];
        return MeshPoint{f.object, f.triangle, f.bary[i % 3]};
    };
    std::vector<int> positions(static_cast<std::size_t>(count), 1);
    const double farthest_bend = std::sqrt(0.5 * layout.reach / kBendTolerance);  // infinite reach: infinite
    const double h = (t1 - t0) / count;
    for (int k = 0; k < count; ++k) {
        const MotionSnapshot begin(scene, projection, t0 + k * h), middle(scene, projection, t0 + (k + 0.5) * h),
            end(scene, projection, t0 + (k + 1) * h);
        // The max is exact in any order, so the reduction is deterministic.
        const double extent = parallelReduce(
            tbb::blocked_range<std::size_t>(0, vertex_count, 4096), 0.0,
            [&](const tbb::blocked_range<std::size_t>& range, double farthest) {
                for (std::size_t i = range.begin(); i != range.end(); ++i) {
                    const MeshPoint v = vertex(i);
                    const ProjectedPoint a = project(begin, scene, v), m = project(middle, scene, v), b = project(end, scene, v);
                    if (a.behind || m.behind || b.behind) continue;
                    if (layout.exact) {
                        farthest = std::max(farthest, std::min(bendLength(a.raster, m.raster, b.raster), farthest_bend));
                        continue;
                    }
                    const SweepPath path = SweepPath::through({a.raster, a.depth}, {m.raster, m.depth}, {b.raster, b.depth});
                    farthest = std::max(farthest, std::min(pathTravel(path), layout.reach));
                }
                return farthest;
            },
            [](double x, double y) { return std::max(x, y); });
        // Chords integrate exactly, so exact sweep has no kink error to floor.
        const double wanted = layout.exact ? extent / layout.spacing
                                           : kinkSamples(extent, layout.shutter_share / count, layout.spacing);
        positions[static_cast<std::size_t>(k)] = subframeCount(wanted, layout.max_positions);
    }
    return positions;
}

int sharedIntervals(std::span<const SubframePlan> tiles) {
    int intervals = 1;
    for (const SubframePlan& p : tiles) intervals = std::max(intervals, p.count);
    return intervals;
}

double largestReach(std::span<const SubframePlan> tiles) {
    double reach = 0.0;
    for (const SubframePlan& p : tiles)
        if (p.count > 0) reach = std::max(reach, sweepInterval(PixelBounds(), p.max_sweep_pixels, p.count, PixelBounds()).reach);
    return reach;
}

std::vector<IntervalTurns> turnsPerInterval(const Scene& scene, const Projection& projection, double t0, double t1,
                                            std::span<const int> positions) {
    const int intervals = static_cast<int>(positions.size());
    const double h = (t1 - t0) / intervals;
    std::vector<IntervalTurns> turns;
    for (int k = 0; k < intervals; ++k)
        turns.push_back(intervalTurns(scene, projection, t0 + k * h, t0 + (k + 1) * h, positions[static_cast<std::size_t>(k)]));
    return turns;
}

SubframeLayout subframeLayout(const SegmentSpan& span, int n) {
    SubframeLayout layout;
    layout.times = subframeTimes(span.t0, span.t1, std::max(n, 1));
    layout.half = 0.5 * (span.t1 - span.t0) / std::max(n, 1);
    const std::size_t count = layout.times.size();
    layout.factors.assign(count, 1.0);
    layout.tilts.assign(count, 0.0);
    if (span.curve_begin == span.curve_end) return layout;  // a box: every factor exactly 1
    const double interval = 2.0 * layout.half;
    const double slope = (span.curve_end - span.curve_begin) / (span.t1 - span.t0);
    const double mean = 0.5 * (span.curve_begin + span.curve_end);
    for (std::size_t k = 0; k < count; ++k) {
        const double w = span.curve_begin + slope * (layout.times[k] - span.t0);  // > 0 strictly inside the segment
        layout.factors[k] = w / mean;
        layout.tilts[k] = slope * interval / w;
    }
    return layout;
}

}  // namespace clipblur
