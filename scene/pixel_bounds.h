#pragma once

#include <algorithm>
#include <cstddef>
#include <string>

namespace clipblur {

// A half-open rectangle of pixels [x0, x1) x [y0, y1): a tile, an EXR data window, the part of the film a
// render computes. Built only through corners() or sized(), so a width is never read as a corner.
struct PixelBounds {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    PixelBounds() = default;  // user-declared: no aggregate init, whose 4 ints could mean either layout

    static PixelBounds corners(int x0, int y0, int x1, int y1) {
        PixelBounds b;
        b.x0 = x0, b.y0 = y0, b.x1 = x1, b.y1 = y1;
        return b;
    }
    static PixelBounds sized(int x0, int y0, int width, int height) { return corners(x0, y0, x0 + width, y0 + height); }

    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    // Pixel count; 0 when empty.
    std::size_t area() const { return empty() ? 0 : static_cast<std::size_t>(width()) * static_cast<std::size_t>(height()); }
    bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
    // True when the two share a pixel.
    bool overlaps(const PixelBounds& o) const { return !empty() && !o.empty() && o.x0 < x1 && o.x1 > x0 && o.y0 < y1 && o.y1 > y0; }
    // Row-major offset of pixel (x, y), which must be inside.
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y - y0) * static_cast<std::size_t>(width()) + static_cast<std::size_t>(x - x0);
    }
    PixelBounds intersect(const PixelBounds& o) const {
        return corners(std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1));
    }
    PixelBounds unite(const PixelBounds& o) const {
        return corners(std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1));
    }
    friend bool operator==(const PixelBounds&, const PixelBounds&) = default;
};

// "[x0,x1)x[y0,y1)", for messages.
std::string toString(const PixelBounds& b);

}  // namespace clipblur
