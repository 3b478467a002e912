#pragma once

#include <string>

namespace clipblur {

// A rectangle of pixels inside a display window whose origin is (0, 0); half-open: [x0, x0+width).
// The data window of an EXR, of a tile shard, and the part of the film a render computes.
struct DataWindow {
    int x0 = 0;
    int y0 = 0;
    int width = 0;
    int height = 0;

    int x1() const { return x0 + width; }
    int y1() const { return y0 + height; }
    bool empty() const { return width <= 0 || height <= 0; }
    bool contains(int x, int y) const { return x >= x0 && x < x1() && y >= y0 && y < y1(); }
    // True when some pixel of [x0, x1) x [y0, y1) lies inside the window.
    bool overlaps(int ox0, int oy0, int ox1, int oy1) const {
        return !empty() && ox0 < x1() && ox1 > x0 && oy0 < y1() && oy1 > y0;
    }
    friend bool operator==(const DataWindow&, const DataWindow&) = default;
};

// "[x0,x1)x[y0,y1)", for messages.
std::string toString(const DataWindow& w);

}  // namespace clipblur
