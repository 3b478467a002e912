#include "renderer/fragments/fragment_tile.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

// Triangle ti's part in pixel (x, y), cut from its strip of row y, which is clipped once per row; false
// where the strip does not reach the pixel's column, or touches it only along its side (the clip would
// give at most a segment, or a zero-area sliver the resolver drops).
bool pixelPiece(TileScratch& scratch, std::uint32_t ti, int x, int y, ConvexPolygon& piece) {
    if (scratch.strip_row[ti] != y) {
        const ConvexPolygon& strip = scratch.strips[ti].poly;
        scratch.clippers[ti].clipToStrip(y, y + 1.0, scratch.strips[ti]);
        scratch.strip_row[ti] = y;
        glm::dvec2 span(std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity());
        if (!strip.degenerate())
            for (int k = 0; k < strip.n; ++k) span = {std::min(span.x, strip.v[k].x), std::max(span.y, strip.v[k].x)};
        scratch.strip_x[ti] = span;
    }
    const glm::dvec2& span = scratch.strip_x[ti];
    if (span.y <= x || span.x >= x + 1.0) return false;
    scratch.clippers[ti].clipToColumn(scratch.strips[ti], x, x + 1.0, piece);
    return true;
}

// Coverage a layer's pieces of one surface may miss and still cover a pixel wholly: the cracks rounding
// leaves along edges that pieces share (~1e-15 px^2 each), well below the audit's 1e-9 px^2 per pixel; a
// real hole is larger.
constexpr double kWholeSlack = 1e-10;
// Pieces smaller than this (px^2) are not asked which surface is in front: a sliver's plane, carried to
// the pixel's centre, is ill-conditioned. The choice only decides which surface is tried.
constexpr double kFrontCandidateArea = 1e-2;

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

// Pixel (x, y) as one fragment, the pixel itself, when one surface S (ScreenTriangle::surface) is in front
// over all of it: S's pieces cover it wholly from each layer they come from (a layer's pieces of one
// surface do not overlap), S's planes from both layers coincide, and every other piece lies behind S. What
// the resolver would give, to rounding, without clipping the pieces against each other. S is tried as the
// surface nearest at the pixel's centre; each layer's source is its largest piece of S, whose triangle is
// best conditioned for evaluating the surface across the pixel. Pieces are pixel-local.
bool wholePixel(std::span<const ScreenTriangle> triangles, std::span<const PixelPiece> pieces, const glm::dvec2& pixel,
                const ResolverSettings& settings, Fragment& out) {
    const glm::dvec2 centre(0.5, 0.5);
    const PixelPiece* front = nullptr;
    for (const PixelPiece& p : pieces)
        if (p.area >= kFrontCandidateArea && (!front || p.plane(centre) > front->plane(centre))) front = &p;
    if (!front) return false;
    const std::uint64_t surface = triangles[front->triangle].surface;
    if (surface == ScreenTriangle::kNoSurface) return false;

    std::array<double, 2> covered{0.0, 0.0};
    std::array<const PixelPiece*, 2> largest{nullptr, nullptr};
    for (const PixelPiece& p : pieces) {
        if (triangles[p.triangle].surface != surface) continue;
        const int layer = triangles[p.triangle].layer;
        covered[layer] += p.area;
        if (!largest[layer] || p.area > largest[layer]->area) largest[layer] = &p;
    }
    for (int layer = 0; layer < 2; ++layer)
        if (largest[layer] && !(std::abs(covered[layer] - 1.0) <= kWholeSlack)) return false;
    // Counter-clockwise, as resolved fragments are.
    const std::array<glm::dvec2, 4> corners{glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(1, 1), glm::dvec2(0, 1)};
    const DepthPlane& plane = (largest[0] ? largest[0] : largest[1])->plane;
    if (largest[0] && largest[1] && !coincide(plane, largest[1]->plane, corners, settings.coincident_rel)) return false;
    for (const PixelPiece& p : pieces) {
        if (triangles[p.triangle].surface == surface) continue;
        if (!behind(plane, p.plane, std::span(p.poly.v.data(), std::size_t(p.poly.n)), settings.coincident_rel))
            return false;
    }
    out = Fragment();
    out.vertex_count = 4;
    for (int k = 0; k < 4; ++k) out.vertices[k] = pixel + corners[k];
    for (int layer = 0; layer < 2; ++layer) {
        if (!largest[layer]) continue;
        const ScreenTriangle& t = triangles[largest[layer]->triangle];
        out.sources[out.source_count++] = FragmentSource{t.source, t.layer, t.weight};
    }
    out.area = 1.0;
    return true;
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
    for (std::size_t ti = 0; ti < triangles.size(); ++ti) {
        const ScreenTriangle& t = triangles[ti];
        scratch.clippers.emplace_back(t.raster);
        if (!validScreenTriangle(t) || !scratch.clippers.back().valid()) {
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
        const int x_begin = std::max(rect.x0, int(std::floor(std::max(lox, double(rect.x0)))));
        const int x_end = std::min(rect.x1 - 1, int(std::floor(std::min(hix, double(rect.x1)))));
        const int y_begin = std::max(rect.y0, int(std::floor(std::max(loy, double(rect.y0)))));
        const int y_end = std::min(rect.y1 - 1, int(std::floor(std::min(hiy, double(rect.y1)))));
        const double nearest = std::max({t.inv_depth[0], t.inv_depth[1], t.inv_depth[2]});
        for (int y = y_begin; y <= y_end; ++y) {
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
        if (triangles[begin->triangle].surface == ScreenTriangle::kNoSurface) {
            for (auto it = begin; it != end; ++it)
                if (pixelPiece(scratch, it->triangle, x, y, piece)) resolver.insertClipped(triangles[it->triangle], piece);
        } else {
            scratch.pixel_pieces.clear();
            PixelPiece prepared;
            for (auto it = begin; it != end; ++it)
                if (pixelPiece(scratch, it->triangle, x, y, piece) &&
                    resolver.prepare(triangles[it->triangle], it->triangle, piece, prepared))
                    scratch.pixel_pieces.push_back(prepared);
            Fragment whole;
            if (wholePixel(triangles, scratch.pixel_pieces, glm::dvec2(x, y), settings, whole)) {
                out.fragments.push_back(whole);
                CLIPBLUR_DCHECK(wellFormed(whole, x, y));
                out.covered_area[i] = 1.0;
                out.dropped_area += resolver.droppedArea();
                continue;
            }
            for (const PixelPiece& p : scratch.pixel_pieces) resolver.insertPrepared(triangles[p.triangle], p);
        }
        resolver.appendFragments(out.fragments);
        for (std::size_t f = first; f < out.fragments.size(); ++f) CLIPBLUR_DCHECK(wellFormed(out.fragments[f], x, y));
        out.covered_area[i] = resolver.coveredArea();
        out.dropped_area += resolver.droppedArea();
    }
    out.offsets[npix] = std::uint32_t(out.fragments.size());
}

}  // namespace clipblur
