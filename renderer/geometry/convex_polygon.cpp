#include "renderer/geometry/convex_polygon.h"

#include <algorithm>

#include <glm/common.hpp>

#include "renderer/geometry/predicates.h"

namespace clipblur {

namespace {

// The crossing point of edge (a, b) with the zero of an affine function taking values sa at a and sb at b
// (opposite signs). Computed from the lexicographically smaller endpoint so that a neighbouring piece that
// walks the same edge in the other direction gets the identical point.
glm::dvec2 crossing(const glm::dvec2& a, double sa, const glm::dvec2& b, double sb) {
    const bool swap = (b.x < a.x) || (b.x == a.x && b.y < a.y);
    const glm::dvec2& p = swap ? b : a;
    const glm::dvec2& q = swap ? a : b;
    const double sp = swap ? sb : sa;
    const double sq = swap ? sa : sb;
    const double t = sp / (sp - sq);  // in [0, 1] since sp and sq have opposite signs
    return {std::fma(t, q.x - p.x, p.x), std::fma(t, q.y - p.y, p.y)};
}

// Whether every vertex of q lies on or left of the line a -> b (orient2d >= 0).
bool leftOfLine(const ConvexPolygon& q, const glm::dvec2& a, const glm::dvec2& b) {
    for (int i = 0; i < q.n; ++i)
        if (orient2d(a, b, q.v[i]) < 0.0) return false;
    return true;
}

}  // namespace

ConvexPolygon ConvexPolygon::triangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    ConvexPolygon p;
    p.v[0] = a;
    if (orient2d(a, b, c) >= 0.0) {
        p.v[1] = b;
        p.v[2] = c;
    } else {
        p.v[1] = c;
        p.v[2] = b;
    }
    p.n = 3;
    return p;
}

double ConvexPolygon::area() const {
    if (n < 3) return 0.0;
    CompensatedSum sum;
    for (int i = 1; i + 1 < n; ++i) sum.add(orient2d(v[0], v[i], v[i + 1]));
    return 0.5 * sum.value();
}

RasterBounds ConvexPolygon::bounds() const {
    RasterBounds b{v[0], v[0]};
    for (int i = 1; i < n; ++i) {
        b.lo = glm::min(b.lo, v[i]);
        b.hi = glm::max(b.hi, v[i]);
    }
    return b;
}

void splitByValues(const ConvexPolygon& p, const double* s, ConvexPolygon& inside, ConvexPolygon& outside) {
    inside.clear();
    outside.clear();
    for (int i = 0; i < p.n; ++i) {
        const int j = i + 1 == p.n ? 0 : i + 1;
        const double si = s[i];
        const double sj = s[j];
        if (si >= 0.0) inside.push(p.v[i]);
        if (si <= 0.0) outside.push(p.v[i]);
        if ((si > 0.0 && sj < 0.0) || (si < 0.0 && sj > 0.0)) {
            const glm::dvec2 x = crossing(p.v[i], si, p.v[j], sj);
            inside.push(x);
            outside.push(x);
        }
    }
    inside.close();
    outside.close();
}

void clipByValues(const ConvexPolygon& p, const double* s, ConvexPolygon& inside) {
    inside.clear();
    for (int i = 0; i < p.n; ++i) {
        const int j = i + 1 == p.n ? 0 : i + 1;
        const double si = s[i];
        const double sj = s[j];
        if (si >= 0.0) inside.push(p.v[i]);
        if ((si > 0.0 && sj < 0.0) || (si < 0.0 && sj > 0.0)) inside.push(crossing(p.v[i], si, p.v[j], sj));
    }
    inside.close();
}

void clipByLine(const ConvexPolygon& p, const glm::dvec2& a, const glm::dvec2& b, ConvexPolygon& inside) {
    std::array<double, kMaxPolygonVertices> s;
    for (int i = 0; i < p.n; ++i) s[i] = orient2d(a, b, p.v[i]);
    clipByValues(p, s.data(), inside);
}

bool supportingEdge(const ConvexPolygon& q, int e) {
    // Rounded crossing points can leave a polygon very slightly non-convex around a very short edge (or a
    // cluster of nearly equal vertices). The line through such an edge's end points has an arbitrary
    // direction and cuts through the polygon, so using it as a half-plane would remove real area from q:
    // a later polygon would keep that area and overlap q (found by the fragment audit). A short edge with
    // any vertex strictly outside its line is skipped; the half-planes left contain q and differ from it by
    // less than the edge length times the rounding, far below 1e-9 px^2 at this threshold.
    constexpr double kShortEdge = 1e-6;
    const glm::dvec2& a = q.v[e];
    const glm::dvec2& b = q.v[e + 1 == q.n ? 0 : e + 1];
    const glm::dvec2 d = b - a;
    return std::abs(d.x) + std::abs(d.y) >= kShortEdge || q.n < 4 || leftOfLine(q, a, b);
}

namespace {

// A line through a and b bounding q: q lies on its left (orient2d(a, b, x) >= 0).
struct BoundingLine {
    glm::dvec2 a{0.0}, b{0.0};
};

// q's bounding lines in edge order: its supporting edges, and for each run of skipped edges (a cluster of
// nearly equal vertices bent by rounding) the chord from the run's first vertex to its last where that
// bounds q. Without it the edges on either side of the cluster were its only bounds, and where they are
// nearly parallel (a sliver's sides) their half-planes reached far past q: the fragment audit found a
// 0.16 px strip kept as overlap (FragmentAudit.SliverWithADentedEndRegression).
int boundingLines(const ConvexPolygon& q, std::array<BoundingLine, kMaxPolygonVertices>& lines) {
    int first = 0;
    while (first < q.n && !supportingEdge(q, first)) ++first;
    if (first == q.n) return 0;
    int count = 0;
    for (int k = 0; k < q.n; ++k) {
        const int e = (first + k) % q.n;
        if (supportingEdge(q, e)) {
            lines[count++] = {q.v[e], q.v[(e + 1) % q.n]};
            continue;
        }
        int last = e;  // the run of skipped edges e .. last
        for (; k + 1 < q.n && !supportingEdge(q, (last + 1) % q.n); ++k) last = (last + 1) % q.n;
        const glm::dvec2& a = q.v[e];
        const glm::dvec2& b = q.v[(last + 1) % q.n];
        if (a != b && leftOfLine(q, a, b)) lines[count++] = {a, b};
    }
    return count;
}

}  // namespace

bool splitByConvex(const ConvexPolygon& p, const ConvexPolygon& q, std::vector<ConvexPolygon>& outside,
                   ConvexPolygon& inside) {
    std::array<double, kMaxPolygonVertices> s;
    std::array<BoundingLine, kMaxPolygonVertices> lines;
    const int count = boundingLines(q, lines);
    ConvexPolygon rest = p;
    ConvexPolygon in;
    ConvexPolygon out;
    for (int l = 0; l < count; ++l) {
        bool any_in = false;
        bool any_out = false;
        for (int i = 0; i < rest.n; ++i) {
            s[i] = orient2d(lines[l].a, lines[l].b, rest.v[i]);
            any_in |= s[i] > 0.0;
            any_out |= s[i] < 0.0;
        }
        if (!any_out) continue;  // rest lies on the inner side of this edge line
        if (!any_in) {
            // Nothing of rest is strictly inside this edge: the intersection is empty.
            outside.push_back(rest);
            inside.clear();
            return false;
        }
        splitByValues(rest, s.data(), in, out);
        if (!out.degenerate()) outside.push_back(out);
        rest = in;
        if (rest.degenerate()) break;
    }
    inside = rest;
    return true;
}

void intersect(const ConvexPolygon& p, const ConvexPolygon& q, ConvexPolygon& out) {
    std::array<BoundingLine, kMaxPolygonVertices> lines;
    const int count = boundingLines(q, lines);
    ConvexPolygon rest = p;
    for (int l = 0; l < count && !rest.degenerate(); ++l) {
        clipByLine(rest, lines[l].a, lines[l].b, out);
        rest = out;
    }
    out = rest;
}

void splitToCapacity(const ConvexPolygon& p, int max_vertices, std::vector<ConvexPolygon>& out) {
    if (p.n <= max_vertices) {
        out.push_back(p);
        return;
    }
    // Fan groups around v[0]: vertices 0, k, k+1, ..., k+max_vertices-2; consecutive groups share the
    // diagonal v[0]-v[k+max_vertices-2], and each group is convex as a sub-polygon of a convex polygon.
    int k = 1;
    while (k + 1 < p.n) {
        const int last = std::min(p.n - 1, k + max_vertices - 2);
        ConvexPolygon part;
        part.push(p.v[0]);
        for (int i = k; i <= last; ++i) part.push(p.v[i]);
        part.close();
        if (!part.degenerate()) out.push_back(part);
        k = last;
    }
}

}  // namespace clipblur
