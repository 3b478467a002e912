#pragma once

#include <cstdint>
#include <vector>

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
    // The index of the tile holding pixel (x, y), which must be inside the grid.
    int indexOf(int x, int y) const { return ((y - y0_) / size_) * columns_ + (x - x0_) / size_; }
    // The tiles [tx0, tx1) x [ty0, ty1) (column, row) that overlap `box`; empty when none do.
    PixelBounds tilesOverlapping(const PixelBounds& box) const;

private:
    int x0_ = 0;
    int y0_ = 0;
    int width_;
    int height_;
    int size_;
    int columns_;
    int rows_;
};

// A set of a TileGrid's tiles, by index: where a shutter segment's fragment sets keep every layer
// (ShutterSegment::deep). Default: every tile, of any grid.
class TileSet {
public:
    TileSet() = default;
    static TileSet none() { return TileSet(false); }

    bool every() const { return every_; }
    bool contains(int index) const {
        return every_ || (index >= 0 && static_cast<std::size_t>(index) < in_.size() && in_[static_cast<std::size_t>(index)] != 0);
    }
    bool empty() const;
    // Members among the grid's tiles.
    int size(const TileGrid& grid) const;
    // Adds the tiles of `grid` that overlap `box`.
    void addOverlapping(const TileGrid& grid, const PixelBounds& box);
    // The tiles of `to` that overlap a member tile of `grid` grown by `margin` pixels on each side.
    TileSet grown(const TileGrid& grid, int margin, const TileGrid& to) const;
    TileSet unite(const TileSet& other) const;

private:
    explicit TileSet(bool every) : every_(every) {}
    bool every_ = true;
    std::vector<std::uint8_t> in_;  // !every_: 1 for a member, by index; missing indices are not members
};

}  // namespace clipblur
