#include "renderer/fragments/fragment_tile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "renderer/check.h"
#include "renderer/geometry/predicates.h"

namespace clipblur {

namespace {

// What every consumer of a resolved fragment relies on (the sanitizer build checks it; render.audit
// checks more, against an independent union): finite vertices inside pixel (x, y) up to the audit's
// 1e-9 px, counter-clockwise turns, a positive finite area, and mix factors summing to 1.
[[maybe_unused]] bool wellFormed(const Fragment& f, int x, int y) {
    constexpr double kOutside = 1e-9;  // px, AuditTolerance::outside
    if (f.vertex_count < 3 || f.source_count < 1 || !(f.area > 0.0) || !std::isfinite(f.area)) return false;
    for (int k = 0; k < f.vertex_count; ++k) {
        const glm::dvec2& v = f.vertices[k];
        if (!(v.x >= x - kOutside && v.x <= x + 1 + kOutside && v.y >= y - kOutside && v.y <= y + 1 + kOutside))
            return false;  // also NaN
        // Convex and counter-clockwise: no turn to the right (collinear runs are allowed).
        if (orient2d(v, f.vertices[(k + 1) % f.vertex_count], f.vertices[(k + 2) % f.vertex_count]) < -1e-10)
            return false;  // px^2: rounding of clipped vertices, far below any real turn
    }
    return std::abs(f.mix(0) + (f.source_count > 1 ? f.mix(1) : 0.0) - 1.0) < 1e-12;
}

// Binning widens a triangle's row extent by this much (px): the extent's edge crossings are computed
// apart from the clipper's and may differ from them by rounding (~1e-13 px at raster coordinates of
// 1e3), so a pixel the clip reaches is never missed; one it only touches yields no piece.
constexpr double kBinSlack = 1e-9;

// The x extent of triangle v within the row y0 <= y <= y1 (lo > hi where it misses the row): from its
// vertices in the row and its edges' crossings of the row's lines, where the extremes of a convex
// polygon's cut lie.
glm::dvec2 rowExtent(const std::array<glm::dvec2, 3>& v, double y0, double y1) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    glm::dvec2 extent(kInf, -kInf);
    const auto add = [&](double x) { extent = {std::min(extent.x, x), std::max(extent.y, x)}; };
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2& p = v[i];
        const glm::dvec2& q = v[(i + 1) % 3];
        if (p.y >= y0 && p.y <= y1) add(p.x);
        for (const double c : {y0, y1})
            if ((p.y < c && q.y > c) || (p.y > c && q.y < c)) add(p.x + (c - p.y) / (q.y - p.y) * (q.x - p.x));
    }
    return extent;
}

// Clips triangle ti to row y once per row, keeping the strip's x extent and the x range over which it
// holds whole pixel columns: a convex polygon's left boundary x is convex in y and its right one concave,
// so the columns wholly inside run from the larger of its left ends at y and y + 1 to the smaller of its
// right ends. Cut vertices lie on the row's lines exactly (TriangleClipper), so comparing y is exact.
void clipRow(TileScratch& scratch, std::uint32_t ti, int y) {
    if (scratch.strip_row[ti] == y) return;
    const ConvexPolygon& strip = scratch.strips[ti].poly;
    scratch.clippers[ti].clipToStrip(y, y + 1.0, scratch.strips[ti]);
    scratch.strip_row[ti] = y;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    glm::dvec2 span(kInf, -kInf);
    std::array<glm::dvec2, 2> ends{glm::dvec2(kInf, -kInf), glm::dvec2(kInf, -kInf)};  // at y, y + 1
    if (!strip.degenerate()) {
        for (int k = 0; k < strip.n; ++k) {
            const glm::dvec2& v = strip.v[k];
            span = {std::min(span.x, v.x), std::max(span.y, v.x)};
            if (v.y == y || v.y == y + 1.0) {
                glm::dvec2& end = ends[v.y == y ? 0 : 1];
                end = {std::min(end.x, v.x), std::max(end.y, v.x)};
            }
        }
    }
    scratch.strip_x[ti] = span;
    scratch.strip_inner[ti] = {std::max(ends[0].x, ends[1].x), std::min(ends[0].y, ends[1].y)};
}

// Triangle ti's part in pixel (x, y), cut from its strip of row y; false where the strip does not reach
// the pixel's column, or touches it only along its side (the clip would give at most a segment, or a
// zero-area sliver the resolver drops).
bool pixelPiece(TileScratch& scratch, std::uint32_t ti, int x, int y, ConvexPolygon& piece) {
    clipRow(scratch, ti, y);
    const glm::dvec2& span = scratch.strip_x[ti];
    if (span.y <= x || span.x >= x + 1.0) return false;
    scratch.clippers[ti].clipToColumn(scratch.strips[ti], x, x + 1.0, piece);
    return true;
}

// Whether triangle ti covers pixel (x, y) wholly (its clip to the pixel would be the pixel itself).
bool containsPixel(TileScratch& scratch, std::uint32_t ti, int x, int y) {
    clipRow(scratch, ti, y);
    return scratch.strip_inner[ti].x <= x && x + 1.0 <= scratch.strip_inner[ti].y;
}

// Whether the planes p and q coincide (the resolver's test) at every point of the pixel-local polygon.
// Both are affine, so the vertices decide.
bool coincide(const DepthPlane& p, const DepthPlane& q, std::span<const glm::dvec2> at, double rel) {
    return std::all_of(at.begin(), at.end(), [&](const glm::dvec2& v) {
        return compareDepth(p(v), q(v), rel) == DepthOrder::Coincident;
    });
}

// Whether plane q lies behind p (farther by more than the resolver's tolerance) over the pixel-local
// polygon: true at its vertices, hence over it (d = p - q is affine and the tolerance convex).
bool behind(const DepthPlane& p, const DepthPlane& q, std::span<const glm::dvec2> at, double rel) {
    return std::all_of(at.begin(), at.end(), [&](const glm::dvec2& v) {
        return compareDepth(p(v), q(v), rel) == DepthOrder::Nearer;
    });
}

// One pixel being resolved: the tile's triangles, the pixel's entries front to back, and the tile's scratch.
struct PixelAt {
    std::span<const ScreenTriangle> triangles;
    std::span<const TileScratch::Entry> entries;
    int x = 0;
    int y = 0;
    const ResolverSettings& settings;
    TileScratch& scratch;
};

// Triangle ti's inverse-depth plane relative to the pixel: inverseDepthPlane's, from slopes found once.
bool planeAt(const PixelAt& at, std::uint32_t ti, DepthPlane& plane) {
    return anchorPlane(at.triangles[ti], at.scratch.slopes[ti], glm::dvec2(at.x, at.y), plane);
}

// Triangle ti's area in the pixel, measured pixel-local as the resolver measures it; 0 for a sliver it
// would drop. `piece` gets the pixel-local part (empty when the triangle contains the pixel or misses it).
double pixelArea(const PixelAt& at, std::uint32_t ti, ConvexPolygon& piece) {
    piece.clear();
    if (containsPixel(at.scratch, ti, at.x, at.y)) return 1.0;
    if (!pixelPiece(at.scratch, ti, at.x, at.y, piece) || piece.degenerate()) return 0.0;
    for (int k = 0; k < piece.n; ++k) piece.v[k] -= glm::dvec2(at.x, at.y);  // exact
    const double area = piece.area();
    return area > at.settings.min_area ? area : 0.0;
}

// One surface tried for a whole pixel: the pixel if S covers it, else which triangle of another surface
// is not behind S there (none when S does not cover the pixel).
struct WholeTry {
    bool whole = false;
    std::optional<std::uint32_t> in_front;
};

// Pixel (x, y) as one fragment, the pixel itself, when surface S (ScreenTriangle::surface) is in front over
// all of it: S's triangles cover it wholly from each layer they reach it from (a layer's triangles of
// one surface do not overlap, so their areas there add up), S's planes from both layers coincide, and
// every other triangle lies behind S at the pixel's corners, or else at the vertices of its part in the
// pixel, or misses it (d - tolerance is concave, so the vertices decide). What the resolver would give,
// to rounding, without clipping pieces against each other; only triangles that neither contain the pixel
// nor lie behind S are clipped. Each layer's source is its largest part of S, whose triangle is best
// conditioned for evaluating the surface across the pixel. `plane` is S's, relative to the pixel.
WholeTry trySurface(const PixelAt& at, std::uint64_t surface, const DepthPlane& plane, Fragment& out) {
    const double rel = at.settings.coincident_rel;
    // Counter-clockwise, as resolved fragments are.
    const std::array<glm::dvec2, 4> corners{glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(1, 1), glm::dvec2(0, 1)};
    std::array<double, 2> covered{0.0, 0.0};
    std::array<double, 2> largest_area{0.0, 0.0};
    std::array<std::uint32_t, 2> largest{0, 0};
    ConvexPolygon piece;
    for (const TileScratch::Entry& e : at.entries) {
        const ScreenTriangle& t = at.triangles[e.triangle];
        if (t.surface == surface) {
            const double area = pixelArea(at, e.triangle, piece);
            covered[t.layer] += area;
            if (area > largest_area[t.layer]) largest_area[t.layer] = area, largest[t.layer] = e.triangle;
            continue;
        }
        DepthPlane q;
        if (!planeAt(at, e.triangle, q)) return {};
        if (behind(plane, q, corners, rel)) continue;
        if (pixelArea(at, e.triangle, piece) == 0.0) continue;
        const std::span<const glm::dvec2> vertices =
            piece.n > 0 ? std::span<const glm::dvec2>(piece.v.data(), std::size_t(piece.n)) : std::span(corners);
        if (!behind(plane, q, vertices, rel)) return {false, e.triangle};
    }
    for (int layer = 0; layer < 2; ++layer)
        if (largest_area[layer] > 0.0 && !(std::abs(covered[layer] - 1.0) <= kFullPixelSlack)) return {};
    if (largest_area[0] == 0.0 && largest_area[1] == 0.0) return {};
    if (largest_area[0] > 0.0 && largest_area[1] > 0.0) {
        DepthPlane p0, p1;
        if (!planeAt(at, largest[0], p0) || !planeAt(at, largest[1], p1) || !coincide(p0, p1, corners, rel))
            return {};
    }
    out = Fragment();
    out.vertex_count = 4;
    for (int k = 0; k < 4; ++k) out.vertices[k] = glm::dvec2(at.x, at.y) + corners[k];
    for (int layer = 0; layer < 2; ++layer) {
        if (largest_area[layer] == 0.0) continue;
        const ScreenTriangle& t = at.triangles[largest[layer]];
        out.sources[out.source_count++] = FragmentSource{t.source, t.layer, t.weight};
    }
    out.area = 1.0;
    return {true, std::nullopt};
}

// Tries the surface of the first triangle (front to back) that contains the pixel, else of the first that
// reaches it, then in turn the surface of a triangle found in front of the one tried, up to three.
bool wholePixel(const PixelAt& at, Fragment& out) {
    constexpr int kTries = 3;
    std::optional<std::uint32_t> candidate;
    for (const TileScratch::Entry& e : at.entries)
        if (containsPixel(at.scratch, e.triangle, at.x, at.y)) {
            candidate = e.triangle;
            break;
        }
    ConvexPolygon piece;
    for (auto e = at.entries.begin(); !candidate && e != at.entries.end(); ++e)
        if (pixelArea(at, e->triangle, piece) > 0.0) candidate = e->triangle;
    std::array<std::uint64_t, kTries> tried{};
    for (int k = 0; k < kTries && candidate; ++k) {
        const std::uint64_t surface = at.triangles[*candidate].surface;
        if (surface == ScreenTriangle::kNoSurface || std::find(tried.begin(), tried.begin() + k, surface) != tried.begin() + k)
            return false;
        tried[std::size_t(k)] = surface;
        DepthPlane plane;
        if (!planeAt(at, *candidate, plane)) return false;
        const WholeTry result = trySurface(at, surface, plane, out);
        if (result.whole) return true;
        candidate = result.in_front;
    }
    return false;
}

}  // namespace

void resolveTile(std::span<const ScreenTriangle> triangles, const PixelBounds& rect, const ResolverSettings& settings,
                 TileScratch& scratch, FragmentTile& out) {
    const std::size_t npix = rect.area();
    out.rect = rect;
    out.offsets.assign(npix + 1, 0);
    out.fragments.clear();
    out.covered_area.assign(npix, 0.0);
    out.rejected_triangles = 0;
    out.dropped_area = 0.0;
    if (npix == 0) return;

    scratch.entries.clear();
    scratch.clippers.clear();
    scratch.slopes.resize(triangles.size());
    for (std::size_t ti = 0; ti < triangles.size(); ++ti) {
        const ScreenTriangle& t = triangles[ti];
        scratch.clippers.emplace_back(t.raster);
        if (!validScreenTriangle(t) || !scratch.clippers.back().valid() || !inverseDepthSlopes(t, scratch.slopes[ti])) {
            ++out.rejected_triangles;
            continue;
        }
        double lox = t.raster[0].x, hix = lox, loy = t.raster[0].y, hiy = loy;
        for (int i = 1; i < 3; ++i) {
            lox = std::min(lox, t.raster[i].x);
            hix = std::max(hix, t.raster[i].x);
            loy = std::min(loy, t.raster[i].y);
            hiy = std::max(hiy, t.raster[i].y);
        }
        if (!(hix >= rect.x0 && lox <= rect.x1 && hiy >= rect.y0 && loy <= rect.y1)) {
            continue;
        }
        const int y_begin = std::max(rect.y0, int(std::floor(std::max(loy, double(rect.y0)))));
        const int y_end = std::min(rect.y1 - 1, int(std::floor(std::min(hiy, double(rect.y1)))));
        const double nearest = std::max({t.inv_depth[0], t.inv_depth[1], t.inv_depth[2]});
        for (int y = y_begin; y <= y_end; ++y) {
            const glm::dvec2 row = rowExtent(t.raster, y, y + 1.0);
            if (row.x > row.y) continue;
            const int x_begin = std::max(rect.x0, int(std::floor(std::max(row.x - kBinSlack, double(rect.x0)))));
            const int x_end = std::min(rect.x1 - 1, int(std::floor(std::min(row.y + kBinSlack, double(rect.x1)))));
            for (int x = x_begin; x <= x_end; ++x) {
                const auto pixel = std::uint32_t(rect.index(x, y));
                scratch.entries.push_back({pixel, std::uint32_t(ti), nearest});
            }
        }
    }

    // Counting sort by pixel, then front to back within a pixel.
    scratch.counts.assign(npix + 1, 0);
    for (const auto& e : scratch.entries) ++scratch.counts[e.pixel + 1];
    for (std::size_t i = 0; i < npix; ++i) scratch.counts[i + 1] += scratch.counts[i];
    scratch.sorted.resize(scratch.entries.size());
    {
        std::vector<std::uint32_t>& next = scratch.counts;
        for (const auto& e : scratch.entries) scratch.sorted[next[e.pixel]++] = e;
        // next[i] now holds the end of pixel i; shift back to starts.
        for (std::size_t i = npix; i > 0; --i) next[i] = next[i - 1];
        next[0] = 0;
    }

    scratch.strips.resize(triangles.size());
    scratch.strip_row.assign(triangles.size(), std::numeric_limits<int>::min());
    scratch.strip_x.resize(triangles.size());
    scratch.strip_inner.resize(triangles.size());
    ConvexPolygon piece;
    PixelResolver& resolver = scratch.resolver;
    resolver.setSettings(settings);
    for (std::size_t i = 0; i < npix; ++i) {
        const auto begin = scratch.sorted.begin() + scratch.counts[i];
        const auto end = scratch.sorted.begin() + scratch.counts[i + 1];
        out.offsets[i] = std::uint32_t(out.fragments.size());
        if (begin == end) continue;
        std::sort(begin, end, [](const TileScratch::Entry& a, const TileScratch::Entry& b) {
            return a.nearest != b.nearest ? a.nearest > b.nearest : a.triangle < b.triangle;
        });
        const int x = rect.x0 + int(i % rect.width());
        const int y = rect.y0 + int(i / rect.width());
        const std::size_t first = out.fragments.size();
        resolver.reset(x, y);
        const PixelAt at{triangles, {&*begin, std::size_t(end - begin)}, x, y, settings, scratch};
        Fragment whole;
        if (triangles[begin->triangle].surface != ScreenTriangle::kNoSurface && wholePixel(at, whole)) {
            out.fragments.push_back(whole);
            CLIPBLUR_DCHECK(wellFormed(whole, x, y));
            out.covered_area[i] = 1.0;
            continue;
        }
        DepthPlane plane;
        for (const TileScratch::Entry& e : at.entries)
            if (pixelPiece(scratch, e.triangle, x, y, piece) && planeAt(at, e.triangle, plane))
                resolver.insertClipped(triangles[e.triangle], piece, plane);
        resolver.appendFragments(out.fragments);
        for (std::size_t f = first; f < out.fragments.size(); ++f) CLIPBLUR_DCHECK(wellFormed(out.fragments[f], x, y));
        out.covered_area[i] = resolver.coveredArea();
        out.dropped_area += resolver.droppedArea();
    }
    out.offsets[npix] = std::uint32_t(out.fragments.size());
}

}  // namespace clipblur
