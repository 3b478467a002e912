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

PixelBounds TileGrid::tilesOverlapping(const PixelBounds& box) const {
    const PixelBounds inside = box.intersect(PixelBounds::sized(x0_, y0_, width_, height_));
    if (inside.empty()) return {};
    return PixelBounds::corners((inside.x0 - x0_) / size_, (inside.y0 - y0_) / size_, (inside.x1 - 1 - x0_) / size_ + 1,
                                (inside.y1 - 1 - y0_) / size_ + 1);
}

bool TileSet::empty() const {
    return !every_ && std::none_of(in_.begin(), in_.end(), [](std::uint8_t b) { return b != 0; });
}

int TileSet::size(const TileGrid& grid) const {
    int n = 0;
    for (int i = 0; i < grid.count(); ++i) n += contains(i) ? 1 : 0;
    return n;
}

void TileSet::addOverlapping(const TileGrid& grid, const PixelBounds& box) {
    if (every_) return;
    const PixelBounds t = grid.tilesOverlapping(box);
    if (t.empty()) return;
    in_.resize(static_cast<std::size_t>(grid.count()), 0);
    for (int ty = t.y0; ty < t.y1; ++ty)
        for (int tx = t.x0; tx < t.x1; ++tx) in_[static_cast<std::size_t>(ty * grid.columns() + tx)] = 1;
}

TileSet TileSet::grown(const TileGrid& grid, int margin, const TileGrid& to) const {
    if (every_) return *this;
    TileSet out(false);
    for (int i = 0; i < grid.count(); ++i) {
        if (!contains(i)) continue;
        const PixelBounds t = grid.tile(i);
        out.addOverlapping(to, PixelBounds::corners(t.x0 - margin, t.y0 - margin, t.x1 + margin, t.y1 + margin));
    }
    return out;
}

TileSet TileSet::unite(const TileSet& other) const {
    if (every_ || other.every_) return TileSet();
    TileSet out(false);
    out.in_.resize(std::max(in_.size(), other.in_.size()), 0);
    for (std::size_t i = 0; i < out.in_.size(); ++i)
        out.in_[i] = (i < in_.size() && in_[i]) || (i < other.in_.size() && other.in_[i]) ? 1 : 0;
    return out;
}

}  // namespace clipblur
