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

Tile TileGrid::tile(int index) const {
    const int tx = index % columns_;
    const int ty = index / columns_;
    Tile t;
    t.x0 = tx * size_;
    t.y0 = ty * size_;
    t.x1 = std::min(t.x0 + size_, width_);
    t.y1 = std::min(t.y0 + size_, height_);
    return t;
}

}  // namespace clipblur
