#pragma once

#include <vector>

#include "renderer/shading/image_textures.h"

namespace clipblur {

// One MIP level: linear RGB floats, row 0 the top (t = 0), repeating in both directions.
struct TexelLevel {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;

    // Texel (i, j) of the periodic image, any integers.
    const float* texel(long long i, long long j) const {
        const long long x = ((i % width) + width) % width, y = ((j % height) + height) % height;
        return &rgb[static_cast<std::size_t>(3 * (y * width + x))];
    }
};

// An image's texels in memory as a MIP pyramid, for integrating its bilinear image over polygons
// (renderer/shading/texture_integral.h). Level 0 is the prepared image the texture system's point lookups
// read; each next level halves both sides (rounding down, at least 1) and is the box average in linear
// light of the level above, each coarse texel the exact area mean of the finer texels it covers (so odd
// sides need no padding: a coarse texel then covers fractions of finer ones). The last level is 1 x 1.
class TexelPyramid {
public:
    explicit TexelPyramid(ImageTextures::Texels finest);

    // The pyramid of a prepared image, built on first request and kept while the process runs (prepared
    // images are never released). Thread-safe; empty (no levels) when the texels cannot be read.
    static const TexelPyramid& of(const ImageTextures::Image& image);

    int levels() const { return static_cast<int>(levels_.size()); }
    const TexelLevel& level(int l) const { return levels_[static_cast<std::size_t>(l)]; }

private:
    std::vector<TexelLevel> levels_;
};

}  // namespace clipblur
