#include "renderer/integrate/swept_polygons.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "renderer/clipped/time_error.h"
#include "renderer/geometry/chord_sweep.h"
#include "renderer/thread_scratch.h"

namespace clipblur {

void PolygonObjects::add(int object, double amount) {
    for (int k = 0; k < count; ++k) {
        if (shares[static_cast<std::size_t>(k)].object == object) {
            shares[static_cast<std::size_t>(k)].coverage += amount;
            return;
        }
    }
    // Two sources per fragment, minus a rectangle's two: four entries always suffice.
    if (count == static_cast<int>(shares.size())) throw std::logic_error("PolygonObjects: more than 4 objects");
    shares[static_cast<std::size_t>(count++)] = {object, amount};
}

bool PolygonObjects::none() const {
    return std::all_of(shares.begin(), shares.begin() + count, [](const ObjectShare& s) { return s.coverage == 0.0; });
}

void mergePixel(std::vector<SweptPolygon>& swept, std::size_t begin, std::vector<SweptPolygon>& staging) {
    std::size_t count = 0, base = begin;
    double area = 0.0, largest = -1.0;
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    glm::dvec2 motion(0.0);
    double depth = 0.0;
    for (std::size_t i = begin; i < swept.size(); ++i) {
        const SweptPolygon& e = swept[i];
        if (!e.coverage) continue;
        ++count;
        const double a = e.polygon.area();
        area += a;
        motion += a * e.motion;
        depth += a * e.depth;
        const RasterBounds b = e.polygon.bounds();
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
        if (a > largest) {
            largest = a;
            base = i;
        }
    }
    // Non-overlapping pieces whose areas add up to their bounding box's (to rounding) fill it.
    const double box_area = (hi.x - lo.x) * (hi.y - lo.y);
    if (count < 2 || !(std::abs(box_area - area) <= 1e-9 * box_area)) return;
    // One path serves the pixel only where its pieces also stretch alike (to 1%: 0.01 px over a pixel);
    // two faces meeting at an edge do not (one turning edge-on shrinks to nothing, the other stays).
    const SweepPath& p = swept[base].path;
    for (std::size_t i = begin; i < swept.size(); ++i) {
        const SweepPath& q = swept[i].path;
        if (swept[i].coverage && (glm::any(glm::greaterThan(glm::abs(q.open_stretch - p.open_stretch), glm::dvec2(0.01))) ||
                                  glm::any(glm::greaterThan(glm::abs(q.close_stretch - p.close_stretch), glm::dvec2(0.01)))))
            return;
    }
    staging.clear();
    SweptPolygon rectangle = swept[base];
    rectangle.polygon.clear();
    for (const glm::dvec2& corner : {lo, glm::dvec2(hi.x, lo.y), hi, glm::dvec2(lo.x, hi.y)}) rectangle.polygon.push(corner);
    rectangle.motion = motion / area;
    rectangle.depth = depth / area;
    staging.push_back(rectangle);
    for (std::size_t i = begin; i < swept.size(); ++i) {
        SweptPolygon e = swept[i];
        e.path = rectangle.path;
        e.positions = rectangle.positions;
        if (e.coverage) {
            if (i == base) continue;
            e.colour -= rectangle.colour;
            for (int k = 0; k < rectangle.objects.count; ++k)
                e.objects.add(rectangle.objects.shares[static_cast<std::size_t>(k)].object,
                              -rectangle.objects.shares[static_cast<std::size_t>(k)].coverage);
            if (e.colour == glm::dvec3(0.0) && e.objects.none()) continue;
            e.coverage = false;
        }
        staging.push_back(e);
    }
    swept.resize(begin);
    swept.insert(swept.end(), staging.begin(), staging.end());
}

namespace {

// What polygon p adds to pixel i of `out` for weight w (px^2 of its footprint there): colour and ID
// mattes, and for a fragment (not a texture piece) covered area, motion and depth.
void addSwept(TileSums& out, std::size_t i, double w, const SweptPolygon& p) {
    out.colour[i] += w * p.colour;
    if (out.track_objects)
        for (int k = 0; k < p.objects.count; ++k)
            addShare(out.objects[i], p.objects.shares[static_cast<std::size_t>(k)].object,
                     w * p.objects.shares[static_cast<std::size_t>(k)].coverage);
    if (!p.coverage) return;
    out.covered[i] += w;
    out.motion[i] += w * p.motion;
    out.depth[i] += w * p.depth;
}

// One polygon's weight per cell of a box, summed over its positions, so that a cell takes one addSwept
// (linear in the weight, as the level term is) instead of one per position: positions a few pixels
// apart or closer revisit cells (table1_spin at 1280x720: 1.8 visits a cell at 2 px, 3.2 at 1 px). A cell's sums
// are the current polygon's where `mark` holds its stamp, so nothing is cleared between polygons.
struct CellWeights {
    std::vector<std::uint32_t> mark;
    std::vector<double> weight, level;
    std::vector<std::size_t> touched;  // in first-visit order
    std::uint32_t stamp = 0;

    void start(std::size_t cells) {
        if (mark.size() < cells || stamp == UINT32_MAX) {
            mark.assign(std::max(cells, mark.size()), 0);
            weight.resize(mark.size());
            level.resize(mark.size());
            stamp = 0;
        }
        ++stamp;
        touched.clear();
    }
    void add(std::size_t i, double w, double l) {
        if (mark[i] != stamp) {
            mark[i] = stamp;
            weight[i] = level[i] = 0.0;
            touched.push_back(i);
        }
        weight[i] += w;
        level[i] += l;
    }
};

// Exact sweep (chord_sweep.h): each polygon's chords integrated exactly; the nested rule's difference from
// chords through its coarser knots, where the path does not translate (a translating one's is one exact
// chord either way: 0).
void accumulateChords(const SweepInterval& sweep, std::span<const SweptPolygon> swept, TileSums& out) {
    for (const SweptPolygon& p : swept) {
        const bool levels = out.track_error && p.positions == sweep.positions && p.positions >= 3 && !p.path.translates();
        const glm::dvec4 value(p.colour, p.coverage ? 1.0 : 0.0);
        // Cells beyond sweep.box are skipped: the plan bounds every path inside it.
        const auto add = [&](int x, int y, double w) {
            if (!out.box.contains(x, y)) return;
            const std::size_t i = out.box.index(x, y);
            addSwept(out, i, w, p);
            if (levels) out.d3[i] -= w * value;
        };
        forEachChordCell(p.polygon, p.path, p.positions, add);
        if (!levels) continue;
        const auto coarse = [&](int x, int y, double w) {
            if (out.box.contains(x, y)) out.d3[out.box.index(x, y)] += w * value;
        };
        forEachChordCell(p.polygon, p.path, p.positions, coarse, SweepKnots::Nested);
    }
}

}  // namespace

void accumulateSwept(const SweepInterval& sweep, const PixelBounds& tile, std::span<const SweptPolygon> swept, TileSums& out) {
    PixelBounds box = tile;
    for (const SweptPolygon& p : swept) {
        const RasterBounds b = sweep.exact ? chordBounds(p.polygon, p.path, p.positions) : sweptBounds(p.polygon, p.path, p.positions);
        if (b.empty()) continue;  // exact: edge-on or facing away over the whole interval
        box.x0 = std::min(box.x0, static_cast<int>(std::floor(b.lo.x)));
        box.y0 = std::min(box.y0, static_cast<int>(std::floor(b.lo.y)));
        box.x1 = std::max(box.x1, static_cast<int>(std::ceil(b.hi.x)));
        box.y1 = std::max(box.y1, static_cast<int>(std::ceil(b.hi.y)));
    }
    box = box.intersect(sweep.box);
    out.reset(box);
    if (sweep.exact) {
        accumulateChords(sweep, swept, out);
        return;
    }
    // Only polygons swept over the interval's positions have coarser levels; a still one is the same at all.
    const NestedRule rule(out.track_error ? sweep.positions : 1);
    CellWeights& cells = threadScratch<CellWeights>();
    for (const SweptPolygon& p : swept) {
        const bool levels = out.track_error && p.positions == sweep.positions && p.positions >= 3;
        cells.start(out.box.area());
        // Only cells of out.box are visited: the plan bounds every path inside sweep.box.
        forEachSweptCell(p.polygon, p.path, p.positions, out.box, [&](int x, int y, double w, int k) {
            cells.add(out.box.index(x, y), w, levels ? w * rule.to3[static_cast<std::size_t>(k)] : 0.0);
        });
        const glm::dvec4 value(p.colour, p.coverage ? 1.0 : 0.0);
        for (const std::size_t i : cells.touched) {
            addSwept(out, i, cells.weight[i], p);
            if (levels) out.d3[i] += cells.level[i] * value;
        }
    }
}

}  // namespace clipblur
