#pragma once

#include "scene/pixel_bounds.h"

namespace clipblur {

// Row-major grid of square tiles covering a width x height image; edge tiles are clipped. Tasks are
// numbered 0 .. count()-1 so a parallel loop over a flat index reaches every pixel exactly once.
class TileGrid {
public:
    TileGrid(int width, int height, int tile_size);
    // A grid over [x0, x0 + width) x [y0, y0 + height): the image plus a guard band, for visibility.
    TileGrid(int x0, int y0, int width, int height, int tile_size);

    int count() const { return columns_ * rows_; }
    int tileSize() const { return size_; }
    int x0() const { return x0_; }
    int y0() const { return y0_; }
    int columns() const { return columns_; }
    int rows() const { return rows_; }
    PixelBounds tile(int index) const;

private:
    int x0_ = 0;
    int y0_ = 0;
    int width_;
    int height_;
    int size_;
    int columns_;
    int rows_;
};

}  // namespace clipblur
