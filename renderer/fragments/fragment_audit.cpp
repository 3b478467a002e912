#include "renderer/fragments/fragment_audit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

namespace clipblur {

namespace {

// Areas and distances in a violation: enough digits to show a difference of the tolerance's size.
std::string digits(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.12g", x);
    return text;
}

// A convex polygon in pixel-local coordinates (raster minus the pixel's corner), either orientation.
using Polygon = std::vector<glm::dvec2>;

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

double shoelace(const Polygon& p) {
    double twice = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) twice += cross(p[i], p[(i + 1) % p.size()]);
    return 0.5 * twice;
}

struct Span {
    double lo, hi;
};

Span xSpan(const Polygon& p) {
    Span s{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const glm::dvec2& v : p) {
        s.lo = std::min(s.lo, v.x);
        s.hi = std::max(s.hi, v.x);
    }
    return s;
}

// Abscissae in (0, 1) where the order of cross-section ends can change.
void addEvents(const std::vector<Polygon>& polygons, std::vector<double>& xs) {
    const auto keep = [&xs](double x) {
        if (x > 0.0 && x < 1.0) xs.push_back(x);
    };
    for (const Polygon& p : polygons) {
        for (std::size_t i = 0; i < p.size(); ++i) {
            const glm::dvec2 a = p[i], b = p[(i + 1) % p.size()];
            keep(a.x);
            for (const double level : {0.0, 1.0}) {
                if ((a.y - level) * (b.y - level) < 0.0) keep(a.x + (level - a.y) * (b.x - a.x) / (b.y - a.y));
            }
        }
    }
    for (std::size_t i = 0; i < polygons.size(); ++i) {
        for (std::size_t j = i + 1; j < polygons.size(); ++j) {
            const Polygon& p = polygons[i];
            const Polygon& q = polygons[j];
            for (std::size_t a = 0; a < p.size(); ++a) {
                const glm::dvec2 p0 = p[a], r = p[(a + 1) % p.size()] - p0;
                for (std::size_t b = 0; b < q.size(); ++b) {
                    const glm::dvec2 q0 = q[b], s = q[(b + 1) % q.size()] - q0;
                    const double d = cross(r, s);
                    if (d == 0.0) continue;  // parallel: the two ends never swap order
                    const double t = cross(q0 - p0, s) / d;
                    const double u = cross(q0 - p0, r) / d;
                    if (t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0) keep(p0.x + t * r.x);
                }
            }
        }
    }
}

// Area of the union of convex polygons inside the unit square, by the slab sweep described in the header.
double unionAreaInUnitSquare(const std::vector<Polygon>& polygons) {
    std::vector<double> xs{0.0, 1.0};
    addEvents(polygons, xs);
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    std::vector<Span> spans;
    std::vector<Span> cuts;
    spans.reserve(polygons.size());
    for (const Polygon& p : polygons) spans.push_back(xSpan(p));
    double area = 0.0;
    for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
        const double x = 0.5 * (xs[k] + xs[k + 1]);
        cuts.clear();
        for (std::size_t i = 0; i < polygons.size(); ++i) {
            if (!(spans[i].lo < x && x < spans[i].hi)) continue;
            const Polygon& p = polygons[i];
            Span c{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
            for (std::size_t e = 0; e < p.size(); ++e) {
                const glm::dvec2 a = p[e], b = p[(e + 1) % p.size()];
                if (!(std::min(a.x, b.x) < x && x < std::max(a.x, b.x))) continue;
                const double y = a.y + (x - a.x) * (b.y - a.y) / (b.x - a.x);
                c.lo = std::min(c.lo, y);
                c.hi = std::max(c.hi, y);
            }
            c.lo = std::max(c.lo, 0.0);
            c.hi = std::min(c.hi, 1.0);
            if (c.lo < c.hi) cuts.push_back(c);
        }
        std::sort(cuts.begin(), cuts.end(), [](const Span& a, const Span& b) { return a.lo < b.lo; });
        double length = 0.0, lo = 0.0, hi = -1.0;
        for (const Span& c : cuts) {
            if (c.lo > hi) {
                if (hi > lo) length += hi - lo;
                lo = c.lo;
                hi = c.hi;
            } else {
                hi = std::max(hi, c.hi);
            }
        }
        if (hi > lo) length += hi - lo;
        area += length * (xs[k + 1] - xs[k]);
    }
    return area;
}

// 1/z of triangle t at pixel-local point p, and whether p is inside t by more than `margin` in every
// barycentric coordinate.
struct DepthAt {
    double inv_depth = 0.0;
    bool inside = false;
};

DepthAt depthAt(const ScreenTriangle& t, const glm::dvec2& corner, const glm::dvec2& p, double margin) {
    const glm::dvec2 a = t.raster[0] - corner, b = t.raster[1] - corner, c = t.raster[2] - corner;
    const double total = cross(b - a, c - a);
    const double l0 = cross(c - b, p - b) / total;
    const double l1 = cross(a - c, p - c) / total;
    const double l2 = 1.0 - l0 - l1;
    return {l0 * t.inv_depth[0] + l1 * t.inv_depth[1] + l2 * t.inv_depth[2],
            l0 > margin && l1 > margin && l2 > margin};
}

glm::dvec2 vertexMean(const Polygon& p) {
    glm::dvec2 sum(0.0);
    for (const glm::dvec2& v : p) sum += v;
    return sum / double(p.size());
}

// Records violations of one pixel; the reported one is the least message, so it does not depend on
// the order in which tiles are audited or merged.
class PixelAudit {
public:
    PixelAudit(int x, int y, AuditStats& stats) : x_(x), y_(y), stats_(stats) {}

    void fail(const std::string& what) {
        ++stats_.violations;
        std::ostringstream s;
        s << "pixel (" << x_ << ", " << y_ << "): " << what;
        if (stats_.first_violation.empty() || s.str() < stats_.first_violation) stats_.first_violation = s.str();
    }

private:
    int x_, y_;
    AuditStats& stats_;
};

}  // namespace

void AuditStats::merge(const AuditStats& other) {
    pixels += other.pixels;
    union_pixels += other.union_pixels;
    union_skipped += other.union_skipped;
    if (!other.first_violation.empty() && (first_violation.empty() || other.first_violation < first_violation))
        first_violation = other.first_violation;
    violations += other.violations;
    worst_outside = std::max(worst_outside, other.worst_outside);
    worst_overlap = std::max(worst_overlap, other.worst_overlap);
    worst_coverage = std::max(worst_coverage, other.worst_coverage);
}

std::string AuditStats::worstText() const {
    char text[160];
    std::snprintf(text, sizeof text, "outside %.3g px, overlap %.3g px^2, coverage %.3g px^2", worst_outside,
                  worst_overlap, worst_coverage);
    return text;
}

void auditTile(std::span<const ScreenTriangle> triangles, const FragmentTile& tile, AuditStats& stats,
               const AuditTolerance& tolerance) {
    const PixelBounds& rect = tile.rect;
    const std::size_t npix = rect.area();
    std::vector<std::vector<std::uint32_t>> inputs(npix);
    std::unordered_map<std::uint32_t, std::uint32_t> by_source;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const ScreenTriangle& t = triangles[i];
        by_source.emplace(t.source, std::uint32_t(i));
        if (!validScreenTriangle(t)) continue;
        double lox = t.raster[0].x, hix = lox, loy = t.raster[0].y, hiy = loy;
        for (const glm::dvec2& v : t.raster) {
            lox = std::min(lox, v.x);
            hix = std::max(hix, v.x);
            loy = std::min(loy, v.y);
            hiy = std::max(hiy, v.y);
        }
        const int x0 = std::max(rect.x0, int(std::floor(std::max(lox, double(rect.x0)))));
        const int x1 = std::min(rect.x1 - 1, int(std::floor(std::min(hix, double(rect.x1)))));
        const int y0 = std::max(rect.y0, int(std::floor(std::max(loy, double(rect.y0)))));
        const int y1 = std::min(rect.y1 - 1, int(std::floor(std::min(hiy, double(rect.y1)))));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x)
                inputs[rect.index(x, y)].push_back(std::uint32_t(i));
    }

    std::vector<Polygon> pieces;
    std::vector<Polygon> covers;
    for (int y = rect.y0; y < rect.y1; ++y) {
        for (int x = rect.x0; x < rect.x1; ++x) {
            const std::size_t i = rect.index(x, y);
            const glm::dvec2 corner(x, y);
            PixelAudit audit(x, y, stats);
            ++stats.pixels;
            pieces.clear();
            double sum = 0.0;
            for (const Fragment& f : tile.pixel(x, y)) {
                Polygon p;
                for (int k = 0; k < f.vertex_count; ++k) {
                    const glm::dvec2 v = f.vertices[k] - corner;
                    const double out = std::max({-v.x, v.x - 1.0, -v.y, v.y - 1.0, 0.0});
                    stats.worst_outside = std::max(stats.worst_outside, out);
                    if (out > tolerance.outside) audit.fail("fragment vertex " + digits(out) + " px outside");
                    p.push_back(v);
                }
                if (p.size() < 3 || std::abs(std::abs(shoelace(p)) - f.area) > tolerance.area) {
                    audit.fail("stored area " + digits(f.area) + " is not the fragment's area");
                }
                sum += f.area;
                const auto own = by_source.find(f.sources[0].source);
                if (own == by_source.end()) {
                    audit.fail("fragment source " + std::to_string(f.sources[0].source) + " is not an input");
                } else if (p.size() >= 3 && f.area > tolerance.area) {
                    const glm::dvec2 c = vertexMean(p);
                    const double mine = depthAt(triangles[own->second], corner, c, -1.0).inv_depth;
                    for (const std::uint32_t t : inputs[i]) {
                        const DepthAt other = depthAt(triangles[t], corner, c, 1e-9);
                        if (other.inside && other.inv_depth > mine * (1.0 + tolerance.depth_rel) + 1e-300)
                            audit.fail("triangle " + std::to_string(triangles[t].source) + " is nearer than fragment of " +
                                       std::to_string(f.sources[0].source));
                    }
                }
                pieces.push_back(std::move(p));
            }
            if (std::abs(sum - tile.covered_area[i]) > tolerance.area)
                audit.fail("fragment areas sum to " + digits(sum) + ", covered area is " + digits(tile.covered_area[i]));
            const double fragments_union = unionAreaInUnitSquare(pieces);
            stats.worst_overlap = std::max(stats.worst_overlap, sum - fragments_union);
            if (sum - fragments_union > tolerance.area)
                audit.fail("fragments overlap by " + digits(sum - fragments_union) + " px^2");
            if (int(inputs[i].size()) > tolerance.max_union_inputs) {
                ++stats.union_skipped;
                continue;
            }
            ++stats.union_pixels;
            covers.clear();
            for (const std::uint32_t t : inputs[i]) {
                Polygon p;
                for (const glm::dvec2& v : triangles[t].raster) p.push_back(v - corner);
                covers.push_back(std::move(p));
            }
            const double inputs_union = unionAreaInUnitSquare(covers);
            const double error = std::abs(inputs_union - sum);
            stats.worst_coverage = std::max(stats.worst_coverage, error);
            if (error > tolerance.area + tile.dropped_area)
                audit.fail("fragments cover " + digits(sum) + " px^2, the inputs " + digits(inputs_union));
        }
    }
}

}  // namespace clipblur
