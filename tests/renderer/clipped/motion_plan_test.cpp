#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/clipped/motion_plan.h"

namespace clipblur {

namespace {

// Random swept boxes over a 100 x 70 grid of 16 px tiles (partial tiles at the right and bottom), some
// reaching past the film, some empty; some fragments reach the camera plane, half of those with the whole
// plane as their box (as ShutterPathSampler::measure gives off straight paths).
std::array<std::vector<FragmentMotion>, 2> randomMotion(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> at(-40.0, 140.0), size(0.0, 60.0);
    std::array<std::vector<FragmentMotion>, 2> motion;
    for (auto& layer : motion) {
        layer.resize(300 + seed % 7);
        for (FragmentMotion& fm : layer) {
            const glm::dvec2 lo(at(rng), at(rng));
            fm.swept.expand(lo);
            fm.swept.expand(lo + glm::dvec2(size(rng), size(rng)));
            fm.crosses_near = rng() % 50 == 0;
            if (fm.crosses_near && rng() % 2 == 0) fm.swept = RasterBounds::everything();
        }
    }
    return motion;
}

// Each tile's bin holds, in ref order (layer 0 first, each in index order), exactly the fragments whose
// swept box meets the tile's 16 px cell [x0, x0 + 16) (a partial tile's cell reaches past the film; a
// box ending on a cell's left edge meets it), whether or not it reaches the camera plane: what a search
// of every pair of tile and fragment finds.
TEST(TileBins, HoldWhatOverlapsEachTileInRefOrder) {
    const TileGrid grid(100, 70, 16);
    for (unsigned seed = 1; seed <= 20; ++seed) {
        const auto motion = randomMotion(seed);
        const TileBins bins(grid, motion);
        for (int tile = 0; tile < grid.count(); ++tile) {
            const PixelBounds t = grid.tile(tile);
            const double x0 = t.x0, y0 = t.y0, x1 = t.x0 + 16.0, y1 = t.y0 + 16.0;
            std::vector<std::pair<int, std::uint32_t>> expected, got;
            for (std::uint8_t layer = 0; layer < 2; ++layer)
                for (std::uint32_t i = 0; i < motion[layer].size(); ++i) {
                    const RasterBounds& b = motion[layer][i].swept;
                    const bool overlaps = b.hi.x >= x0 && b.lo.x < x1 && b.hi.y >= y0 && b.lo.y < y1;
                    if (overlaps) expected.emplace_back(layer, i);
                }
            for (const FragmentRef& ref : bins[tile]) got.emplace_back(ref.layer(), ref.index());
            ASSERT_EQ(got, expected) << "seed " << seed << " tile " << tile;
        }
    }
}

}  // namespace

}  // namespace clipblur
