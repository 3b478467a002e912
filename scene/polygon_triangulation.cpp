#include "scene/polygon_triangulation.h"

#include <cmath>

namespace clipblur {

namespace {

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// Emits the triangles of the convex arc face[a..b] (b may wrap past the end) closed by the chord a-b:
// the arc's middle vertex with both ends, then each half.
void splitArc(const PolygonFace& face, std::size_t a, std::size_t b, std::vector<TriangleIndices>& out) {
    if (b - a < 2) return;
    const std::size_t n = face.size();
    const std::size_t m = a + (b - a) / 2;
    out.push_back({face[a % n], face[m % n], face[b % n]});
    splitArc(face, a, m, out);
    splitArc(face, m, b, out);
}

// Counter-clockwise triangle abc contains p, boundary included.
bool inTriangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& p) {
    return cross(b - a, p - a) >= 0.0 && cross(c - b, p - b) >= 0.0 && cross(a - c, p - c) >= 0.0;
}

// Doubly linked ring of the polygon's remaining vertices.
struct Ring {
    const std::vector<glm::dvec2>& p;
    std::vector<std::size_t> prev, next;

    bool convexAt(std::size_t i) const { return cross(p[i] - p[prev[i]], p[next[i]] - p[i]) > 0.0; }

    // An ear: a convex corner whose triangle holds no other remaining reflex vertex (only reflex
    // vertices can lie inside it) apart from copies of its own corners.
    bool isEar(std::size_t i) const {
        if (!convexAt(i)) return false;
        const glm::dvec2 &a = p[prev[i]], &b = p[i], &c = p[next[i]];
        for (std::size_t j = next[next[i]]; j != prev[i]; j = next[j]) {
            if (convexAt(j) || p[j] == a || p[j] == b || p[j] == c) continue;
            if (inTriangle(a, b, c, p[j])) return false;
        }
        return true;
    }

    void unlink(std::size_t i) {
        next[prev[i]] = next[i];
        prev[next[i]] = prev[i];
    }
};

}  // namespace

std::vector<glm::dvec2> projectFace(const std::vector<glm::dvec3>& positions, const PolygonFace& face) {
    const glm::dvec3 origin = positions[face[0]];
    glm::dvec3 normal(0.0);
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
        normal += glm::cross(positions[face[i]] - origin, positions[face[i + 1]] - origin);
    const double length = glm::length(normal);
    glm::dvec3 u(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0);
    if (length > 0.0 && std::isfinite(length)) {
        const glm::dvec3 w = normal / length;
        // The axis least aligned with the normal gives a well-conditioned first tangent.
        const glm::dvec3 a = std::abs(w.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        u = glm::normalize(glm::cross(a, w));
        v = glm::cross(w, u);
    }
    std::vector<glm::dvec2> polygon;
    polygon.reserve(face.size());
    for (const std::uint32_t index : face) {
        const glm::dvec3 d = positions[index] - origin;
        polygon.emplace_back(glm::dot(d, u), glm::dot(d, v));
    }
    return polygon;
}

bool isConvexPolygon(const std::vector<glm::dvec2>& polygon) {
    const std::size_t n = polygon.size();
    double turning = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 e0 = polygon[i] - polygon[(i + n - 1) % n];
        const glm::dvec2 e1 = polygon[(i + 1) % n] - polygon[i];
        const double c = cross(e0, e1);
        // Straight within rounding counts as convex: a fine circle's turns are that small.
        if (c < -1e-12 * glm::length(e0) * glm::length(e1)) return false;
        turning += std::atan2(c, glm::dot(e0, e1));
    }
    // All left turns can still wind twice (a pentagram); convex winds once.
    return std::abs(turning - 2.0 * M_PI) < 1e-6;
}

void triangulateConvex(const PolygonFace& face, std::vector<TriangleIndices>& out) {
    const std::size_t n = face.size();
    if (n < 3) return;
    const std::size_t i1 = n / 3, i2 = 2 * n / 3;
    out.push_back({face[0], face[i1], face[i2]});
    splitArc(face, 0, i1, out);
    splitArc(face, i1, i2, out);
    splitArc(face, i2, n, out);
}

void triangulateByEarClipping(const std::vector<glm::dvec2>& polygon, const PolygonFace& face,
                              std::vector<TriangleIndices>& out) {
    const std::size_t n = face.size();
    if (n < 3) return;
    Ring ring{polygon, std::vector<std::size_t>(n), std::vector<std::size_t>(n)};
    for (std::size_t i = 0; i < n; ++i) {
        ring.prev[i] = (i + n - 1) % n;
        ring.next[i] = (i + 1) % n;
    }
    std::size_t i = 0, remaining = n, misses = 0;
    while (remaining > 3) {
        // A full round without an ear means the polygon crosses itself: clip anyway so the loop ends.
        if (ring.isEar(i) || misses > remaining) {
            out.push_back({face[ring.prev[i]], face[i], face[ring.next[i]]});
            ring.unlink(i);
            --remaining;
            misses = 0;
            i = ring.prev[i];
        } else {
            ++misses;
            i = ring.next[i];
        }
    }
    out.push_back({face[ring.prev[i]], face[i], face[ring.next[i]]});
}

}  // namespace clipblur
