#pragma once

#include <limits>

#include <glm/glm.hpp>

namespace clipblur {

// A closed axis-aligned box in raster space (pixels, real-valued); default constructed it is empty.
struct RasterBounds {
    glm::dvec2 lo{std::numeric_limits<double>::infinity()};
    glm::dvec2 hi{-std::numeric_limits<double>::infinity()};

    static RasterBounds everything() {
        const double inf = std::numeric_limits<double>::infinity();
        return {glm::dvec2(-inf), glm::dvec2(inf)};
    }
    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y); }  // also when a corner is NaN
    void expand(const glm::dvec2& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void pad(double margin) {
        if (empty()) return;
        lo -= margin;
        hi += margin;
    }
    bool contains(const glm::dvec2& p) const { return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y; }
    // Touching boxes overlap, so callers never skip a real overlap.
    bool overlaps(const RasterBounds& o) const {
        return !empty() && !o.empty() && lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y;
    }
};

}  // namespace clipblur
