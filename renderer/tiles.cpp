#include "renderer/tiles.h"

#include <algorithm>
#include <string>

#include "scene/error.h"

namespace clipblur {

TileGrid::TileGrid(int width, int height, int tile_size) : width_(width), height_(height), size_(tile_size) {
    if (width < 0 || height < 0) throw Error(ExitCode::Render, "image size must not be negative");
    if (tile_size < 1) throw Error(ExitCode::Render, "tile size must be at least 1, got " + std::to_string(tile_size));
    columns_ = (width + tile_size - 1) / tile_size;
    rows_ = (height + tile_size - 1) / tile_size;
}

TileGrid::TileGrid(int x0, int y0, int width, int height, int tile_size) : TileGrid(width, height, tile_size) {
    x0_ = x0;
    y0_ = y0;
}

PixelBounds TileGrid::tile(int index) const {
    const int tx = index % columns_;
    const int ty = index / columns_;
    PixelBounds t;
    t.x0 = x0_ + tx * size_;
    t.y0 = y0_ + ty * size_;
    t.x1 = std::min(t.x0 + size_, x0_ + width_);
    t.y1 = std::min(t.y0 + size_, y0_ + height_);
    return t;
}

}  // namespace clipblur
