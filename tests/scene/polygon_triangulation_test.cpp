#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "scene/polygon_triangulation.h"

namespace clipblur {

namespace {

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

struct Polygon {
    std::vector<glm::dvec3> positions;
    PolygonFace face;
};

// n vertices counter-clockwise around the origin in the xy-plane; odd vertices at radius `inner`.
Polygon star(int n, double inner) {
    Polygon p;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * M_PI * i / n, r = i % 2 ? inner : 1.0;
        p.positions.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
        p.face.push_back(static_cast<std::uint32_t>(i));
    }
    return p;
}

double signedArea(const std::vector<glm::dvec2>& p, const TriangleIndices& t) {
    return 0.5 * cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
}

double shoelace(const std::vector<glm::dvec2>& p) {
    double area = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) area += 0.5 * cross(p[i], p[(i + 1) % p.size()]);
    return area;
}

// n - 2 triangles, each of the face's winding, whose areas add up to the polygon's: together with
// positive areas that means they tile it without overlap.
void expectTiling(const std::vector<glm::dvec2>& p, const std::vector<TriangleIndices>& tris) {
    ASSERT_EQ(tris.size(), p.size() - 2);
    double sum = 0.0;
    for (const auto& t : tris) {
        EXPECT_GT(signedArea(p, t), 0.0);
        sum += signedArea(p, t);
    }
    EXPECT_NEAR(sum, shoelace(p), 1e-12 * p.size());
}

// A triangle and an open axis-aligned box share area (separating axes: the box's and the edges').
bool overlaps(const std::array<glm::dvec2, 3>& t, const glm::dvec2& lo, const glm::dvec2& hi) {
    for (int axis = 0; axis < 2; ++axis) {
        const double a = std::min({t[0][axis], t[1][axis], t[2][axis]});
        const double b = std::max({t[0][axis], t[1][axis], t[2][axis]});
        if (b <= lo[axis] || a >= hi[axis]) return false;
    }
    const std::array<glm::dvec2, 4> corners{lo, glm::dvec2(hi.x, lo.y), hi, glm::dvec2(lo.x, hi.y)};
    for (int e = 0; e < 3; ++e) {
        const glm::dvec2 a = t[e], b = t[(e + 1) % 3];
        if (std::none_of(corners.begin(), corners.end(), [&](const glm::dvec2& c) { return cross(b - a, c - a) > 0.0; }))
            return false;
    }
    return true;
}

// A cells x cells grid over the polygon's bounds: pixels of an image the polygon fills.
struct Grid {
    glm::dvec2 lo{std::numeric_limits<double>::infinity()};
    glm::dvec2 side{0.0};
    int cells = 0;

    Grid(const std::vector<glm::dvec2>& p, int n) : cells(n) {
        glm::dvec2 hi(-std::numeric_limits<double>::infinity());
        for (const glm::dvec2& v : p) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        side = (hi - lo) / double(n);
    }
};

// The most triangles sharing one cell ("fragments per pixel").
int mostTrianglesInACell(const std::vector<glm::dvec2>& p, const std::vector<TriangleIndices>& tris, const Grid& g) {
    int most = 0;
    for (int gx = 0; gx < g.cells; ++gx) {
        for (int gy = 0; gy < g.cells; ++gy) {
            const glm::dvec2 lo = g.lo + g.side * glm::dvec2(gx, gy), hi = lo + g.side;
            int count = 0;
            for (const auto& t : tris) count += overlaps({p[t[0]], p[t[1]], p[t[2]]}, lo, hi);
            most = std::max(most, count);
        }
    }
    return most;
}

// The most polygon vertices inside one cell: no triangulation without new vertices can put fewer
// triangles into that cell, since each of those vertices is a corner of one.
int mostVerticesInACell(const std::vector<glm::dvec2>& p, const Grid& g) {
    std::vector<int> count(static_cast<std::size_t>(g.cells * g.cells), 0);
    for (const glm::dvec2& v : p) {
        const int gx = std::clamp(static_cast<int>((v.x - g.lo.x) / g.side.x), 0, g.cells - 1);
        const int gy = std::clamp(static_cast<int>((v.y - g.lo.y) / g.side.y), 0, g.cells - 1);
        ++count[static_cast<std::size_t>(gy * g.cells + gx)];
    }
    return *std::max_element(count.begin(), count.end());
}

}  // namespace

TEST(PolygonTriangulation, ConvexTestTellsWindingAndTurns) {
    const auto square = [](std::vector<glm::dvec2> p) { return isConvexPolygon(p); };
    EXPECT_TRUE(square({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
    EXPECT_TRUE(square({{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}}));  // a straight corner
    EXPECT_FALSE(square({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}));  // an L
    EXPECT_FALSE(square({{0, 0}, {0, 1}, {1, 1}, {1, 0}}));  // clockwise
    // A pentagram turns left at every corner but winds twice.
    std::vector<glm::dvec2> pentagram;
    for (int i = 0; i < 5; ++i) pentagram.emplace_back(std::cos(4 * M_PI * i / 5), std::sin(4 * M_PI * i / 5));
    EXPECT_FALSE(isConvexPolygon(pentagram));
}

TEST(PolygonTriangulation, ProjectionKeepsTheFacesWinding) {
    Polygon p = star(6, 1.0);
    for (glm::dvec3& v : p.positions) v = glm::dvec3(v.x, 2.0, -v.y);  // in the xz-plane, facing +y
    EXPECT_GT(shoelace(projectFace(p.positions, p.face)), 0.0);
    std::reverse(p.face.begin(), p.face.end());
    EXPECT_GT(shoelace(projectFace(p.positions, p.face)), 0.0) << "projected onto the reversed normal";
}

// A circle of n vertices (issue 24's 20,000-gon): n - 2 triangles tiling it, few meeting at any vertex,
// and no pixel-sized cell holding more than its own boundary vertices force plus a log term. A fan
// from one vertex, checked against the same bound, puts every triangle into the apex's cell.
TEST(PolygonTriangulation, ConvexCircleIsSplitIntoFewTrianglesPerCell) {
    for (const int n : {4, 7, 100, 5000, 20000}) {
        SCOPED_TRACE(n);
        const Polygon circle = star(n, 1.0);
        const std::vector<glm::dvec2> p = projectFace(circle.positions, circle.face);
        ASSERT_TRUE(isConvexPolygon(p));
        std::vector<TriangleIndices> tris;
        triangulateConvex(circle.face, tris);
        expectTiling(p, tris);
        std::vector<int> degree(static_cast<std::size_t>(n), 0);
        for (const auto& t : tris)
            for (const std::uint32_t v : t) ++degree[v];
        EXPECT_LE(*std::max_element(degree.begin(), degree.end()), 2.0 * std::log2(n) + 3.0);

        const Grid grid(p, 32);
        const double bound = mostVerticesInACell(p, grid) + 2.0 * std::log2(n) + 3.0;
        EXPECT_LE(mostTrianglesInACell(p, tris, grid), bound);
        std::vector<TriangleIndices> fan;
        for (std::uint32_t i = 1; i + 1 < static_cast<std::uint32_t>(n); ++i) fan.push_back({0, i, i + 1});
        if (n >= 100) {
            EXPECT_GT(mostTrianglesInACell(p, fan, grid), bound);
        }
    }
}

TEST(PolygonTriangulation, EarClippingTilesNonConvexPolygons) {
    for (const int n : {4, 6, 16, 64, 1000}) {
        SCOPED_TRACE(n);
        const Polygon s = star(n, 0.4);
        const std::vector<glm::dvec2> p = projectFace(s.positions, s.face);
        EXPECT_EQ(isConvexPolygon(p), n == 4);
        std::vector<TriangleIndices> tris;
        triangulateByEarClipping(p, s.face, tris);
        expectTiling(p, tris);
    }
    // An L and a comb with collinear runs along its spine.
    const std::vector<glm::dvec2> ell{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    const std::vector<glm::dvec2> comb{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 2}, {2.5, 2}, {2.5, 1}, {2, 1},
                                       {2, 2}, {1.5, 2}, {1.5, 1}, {1, 1}, {1, 2}, {0, 2}};
    for (const auto* p : {&ell, &comb}) {
        PolygonFace face(p->size());
        for (std::size_t i = 0; i < face.size(); ++i) face[i] = static_cast<std::uint32_t>(i);
        std::vector<TriangleIndices> tris;
        triangulateByEarClipping(*p, face, tris);
        expectTiling(*p, tris);
    }
}

}  // namespace clipblur
