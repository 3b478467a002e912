#include "renderer/fragments/pixel_resolver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "renderer/geometry/pixel_clip.h"

namespace clipblur {

namespace {

// Sources (and their surfaces) after surface src is found coincident with a piece holding `sources`: one
// source per layer, within a layer the lower source index wins (z-fighting resolved independently of
// insertion order).
std::uint8_t mergeSources(std::array<FragmentSource, 2>& sources, std::array<std::uint64_t, 2>& surfaces,
                          std::uint8_t count, const FragmentSource& src, std::uint64_t surface) {
    for (int i = 0; i < count; ++i) {
        if (sources[i].layer == src.layer) {
            if (src.source < sources[i].source) sources[i] = src, surfaces[i] = surface;
            return count;
        }
    }
    sources[count] = src;
    surfaces[count++] = surface;
    if (count == 2 && sources[1].layer < sources[0].layer) {
        std::swap(sources[0], sources[1]);
        std::swap(surfaces[0], surfaces[1]);
    }
    return count;
}

}  // namespace

void PixelResolver::reset(int px, int py) {
    px_ = px;
    py_ = py;
    epoch_ = 0;
    pieces_.clear();
    work_.clear();
    fragments_.clear();
    fragments_valid_ = false;
    dropped_area_ = CompensatedSum();
    rejected_ = 0;
}

bool PixelResolver::dropIfSliver(const ConvexPolygon& poly, double& area) {
    area = poly.degenerate() ? 0.0 : poly.area();
    if (area > settings_.min_area) return false;
    dropped_area_.add(std::max(area, 0.0));
    return true;
}

void PixelResolver::insert(const ScreenTriangle& t) {
    if (t.layer > 1) throw std::invalid_argument("ScreenTriangle::layer must be 0 or 1");
    fragments_valid_ = false;
    DepthPlane plane;
    const TriangleClipper clipper(t.raster);
    if (!validScreenTriangle(t) || !clipper.valid() || !inverseDepthPlane(t, glm::dvec2(px_, py_), plane)) {
        ++rejected_;
        return;
    }
    ConvexPolygon piece;
    clipper.clipToPixel(px_, py_, piece);
    insertClipped(t, piece, plane);
}

void PixelResolver::insertClipped(const ScreenTriangle& t, const ConvexPolygon& clipped, const DepthPlane& plane) {
    if (t.layer > 1) throw std::invalid_argument("ScreenTriangle::layer must be 0 or 1");
    fragments_valid_ = false;
    if (clipped.degenerate()) return;  // most pixels of a triangle's box outside it
    ConvexPolygon local = clipped;
    // Exact: every vertex lies in [px, px+1] x [py, py+1].
    for (int i = 0; i < local.n; ++i) local.v[i] -= glm::dvec2(px_, py_);
    double area = 0.0;
    if (dropIfSliver(local, area)) return;
    mine_ = Piece{};
    mine_.plane = plane;
    mine_.sources[0] = FragmentSource{t.source, t.layer, t.weight};
    mine_.surfaces[0] = t.surface;
    insertPolygon(local, area);
}

void PixelResolver::queueWork(const ConvexPolygon& poly, std::size_t start, double area) {
    if (area == kAreaUnknown && dropIfSliver(poly, area)) return;
    if (poly.n <= kMaxStoredVertices) {
        work_.push_back(Work{poly, start, area});
        return;
    }
    capped_.clear();
    splitToCapacity(poly, kMaxStoredVertices, capped_);
    for (const ConvexPolygon& c : capped_) work_.push_back(Work{c, start});
}

bool PixelResolver::hiddenInFullPixel(const ConvexPolygon& local, const DepthPlane& plane) const {
    // d = 1/z_Q - 1/z_P is affine and the tolerance convex, so Q nearer at P's vertices is Q nearer over P.
    CompensatedSum covered;
    for (const Piece& q : pieces_) {
        if (q.dead) continue;
        for (int k = 0; k < local.n; ++k)
            if (compareDepth(q.plane(local.v[k]), plane(local.v[k]), settings_.coincident_rel) != DepthOrder::Nearer)
                return false;
        covered.add(q.area);
    }
    return covered.value() >= 1.0 - kFullPixelSlack;
}

void PixelResolver::insertPolygon(const ConvexPolygon& local, double area) {
    if (hiddenInFullPixel(local, mine_.plane)) return;
    mine_.epoch = ++epoch_;
    work_.clear();
    queueWork(local, 0, area);
    const std::uint64_t surface = mine_.surfaces[0];
    const int layer = mine_.sources[0].layer;
    // A piece lies inside the part of every source it names, and one layer's parts of one surface do not
    // overlap: a piece naming this polygon's surface and layer cannot overlap it.
    const auto disjoint = [&](const Piece& q) {
        if (surface == ScreenTriangle::kNoSurface) return false;
        for (int i = 0; i < q.source_count; ++i)
            if (q.surfaces[i] == surface && q.sources[i].layer == layer) return true;
        return false;
    };
    while (!work_.empty()) {
        const Work w = work_.back();
        work_.pop_back();
        const RasterBounds box = w.poly.bounds();
        bool consumed = false;
        for (std::size_t qi = w.start; qi < pieces_.size() && !consumed; ++qi) {
            const Piece& q = pieces_[qi];
            if (q.dead || q.epoch == epoch_ || !q.box.overlaps(box) || disjoint(q)) continue;
            consumed = resolve(w.poly, qi);
        }
        if (!consumed) addPiece(w.poly, mine_, w.area);
    }
}

bool PixelResolver::resolve(const ConvexPolygon& w, std::size_t qi) {
    outside_.clear();
    ConvexPolygon overlap;
    splitByConvex(w, pieces_[qi].poly, outside_, overlap);
    if (overlap.degenerate()) return false;

    // w is consumed: the parts outside Q go on against the pieces after Q.
    for (const ConvexPolygon& o : outside_) queueWork(o, qi + 1);
    // A sliver overlap is dropped (and accounted) rather than ignored, so pieces never overlap by more
    // than rounding.
    double overlap_area = 0.0;
    if (dropIfSliver(overlap, overlap_area)) return true;

    const Piece q = pieces_[qi];  // a copy: pieces_ may grow below
    const DepthPlane& plane = mine_.plane;
    const FragmentSource& src = mine_.sources[0];
    std::array<double, kMaxPolygonVertices> d;
    bool all_close = true;
    bool any_nearer = false;
    bool any_farther = false;
    for (int k = 0; k < overlap.n; ++k) {
        const double wp = plane(overlap.v[k]);
        const double wq = q.plane(overlap.v[k]);
        d[k] = wp - wq;
        const DepthOrder order = compareDepth(wp, wq, settings_.coincident_rel);
        all_close &= order == DepthOrder::Coincident;
        any_nearer |= order == DepthOrder::Nearer;
        any_farther |= order == DepthOrder::Farther;
    }

    if (all_close) {
        Piece mixed = q;
        mixed.source_count = mergeSources(mixed.sources, mixed.surfaces, q.source_count, src, mine_.surfaces[0]);
        if (mixed.source_count == q.source_count && mixed.sources == q.sources) return true;  // Q wins
        if (mixed.sources[0] == src) mixed.plane = plane;
        mixed.epoch = epoch_;
        shrinkPiece(qi, w, nullptr);
        addPiece(overlap, mixed, overlap_area);
        return true;
    }
    if (!any_farther) {
        shrinkPiece(qi, w, nullptr);
        addPiece(overlap, mine_, overlap_area);
        return true;
    }
    if (!any_nearer) return true;  // P hidden behind Q over the whole overlap

    // Interpenetration: d is affine, so its zero set is a line through the overlap.
    ConvexPolygon nearer;
    ConvexPolygon farther;
    splitByValues(overlap, d.data(), nearer, farther);
    shrinkPiece(qi, w, &farther);
    addPiece(nearer, mine_);
    return true;
}

void PixelResolver::shrinkPiece(std::size_t qi, const ConvexPolygon& w, const ConvexPolygon* keep) {
    const Piece q = pieces_[qi];
    remnants_.clear();
    ConvexPolygon unused;
    splitByConvex(q.poly, w, remnants_, unused);
    if (keep != nullptr) remnants_.push_back(*keep);
    pieces_[qi].dead = true;
    // The first remnant reuses Q's slot so the pieces after it keep their order.
    bool reused = false;
    for (const ConvexPolygon& r : remnants_) {
        double area = 0.0;
        if (dropIfSliver(r, area)) continue;
        capped_.clear();
        splitToCapacity(r, kMaxStoredVertices, capped_);
        for (const ConvexPolygon& c : capped_) {
            double piece_area = 0.0;
            if (dropIfSliver(c, piece_area)) continue;  // a split can leave a sliver of a larger remnant
            Piece p = q;
            p.poly = c;
            p.box = c.bounds();
            p.area = piece_area;
            if (!reused) {
                pieces_[qi] = p;
                reused = true;
            } else {
                pieces_.push_back(p);
            }
        }
    }
    remnants_.clear();
}

void PixelResolver::addPiece(const ConvexPolygon& poly, const Piece& data, double area) {
    if (area == kAreaUnknown && dropIfSliver(poly, area)) return;
    const auto add = [&](const ConvexPolygon& c, double piece_area) {
        Piece p = data;
        p.poly = c;
        p.box = c.bounds();
        p.area = piece_area;
        p.dead = false;
        pieces_.push_back(p);
    };
    if (poly.n <= kMaxStoredVertices) {
        add(poly, area);
        return;
    }
    capped_.clear();
    splitToCapacity(poly, kMaxStoredVertices, capped_);
    for (const ConvexPolygon& c : capped_) {
        double piece_area = 0.0;
        if (!dropIfSliver(c, piece_area)) add(c, piece_area);  // a split can leave a sliver of a larger polygon
    }
}

double PixelResolver::coveredArea() const {
    CompensatedSum sum;
    for (const Piece& p : pieces_) {
        if (!p.dead) sum.add(p.area);
    }
    return sum.value();
}

const std::vector<Fragment>& PixelResolver::fragments() {
    if (fragments_valid_) return fragments_;
    fragments_.clear();
    appendFragments(fragments_);
    fragments_valid_ = true;
    return fragments_;
}

void PixelResolver::appendFragments(std::vector<Fragment>& out) const {
    const glm::dvec2 origin(px_, py_);
    for (const Piece& p : pieces_) {
        if (p.dead) continue;
        Fragment& f = out.emplace_back();
        f.vertex_count = static_cast<std::uint8_t>(p.poly.n);
        for (int i = 0; i < p.poly.n; ++i) f.vertices[i] = p.poly.v[i] + origin;
        f.source_count = p.source_count;
        f.sources = p.sources;
        f.area = p.area;
    }
}

}  // namespace clipblur
