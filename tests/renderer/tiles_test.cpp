#include "renderer/tiles.h"

#include <random>
#include <set>

#include <gtest/gtest.h>

namespace clipblur {

namespace {

// The tiles of `grid` that share a pixel with `box`, by testing every tile.
std::set<int> overlappingByHand(const TileGrid& grid, const PixelBounds& box) {
    std::set<int> out;
    for (int i = 0; i < grid.count(); ++i)
        if (grid.tile(i).overlaps(box)) out.insert(i);
    return out;
}

std::set<int> members(const TileSet& set, const TileGrid& grid) {
    std::set<int> out;
    for (int i = 0; i < grid.count(); ++i)
        if (set.contains(i)) out.insert(i);
    return out;
}

}  // namespace

// Seeded boxes, some past the grid's edges, on grids with an offset origin and clipped edge tiles: the
// tile range and the set built from it agree with testing every tile.
TEST(TileSet, OverlapsMatchTestingEveryTile) {
    std::mt19937 rng(20261127);
    std::uniform_int_distribution<int> corner(-30, 90), extent(0, 40);
    const TileGrid grids[] = {TileGrid(64, 36, 16), TileGrid(-6, -6, 77, 50, 8)};
    for (const TileGrid& grid : grids) {
        for (int trial = 0; trial < 200; ++trial) {
            const int x0 = corner(rng), y0 = corner(rng);
            const PixelBounds box = PixelBounds::sized(x0, y0, extent(rng), extent(rng));
            const std::set<int> expected = overlappingByHand(grid, box);
            TileSet set = TileSet::none();
            set.addOverlapping(grid, box);
            EXPECT_EQ(members(set, grid), expected) << toString(box);
            EXPECT_EQ(set.empty(), expected.empty());
            EXPECT_EQ(set.size(grid), static_cast<int>(expected.size()));
        }
    }
}

// Union against std::set, with "every tile" on either side.
TEST(TileSet, UnionMatchesStdSet) {
    const TileGrid grid(70, 40, 8);
    std::mt19937 rng(7);
    std::bernoulli_distribution coin(0.4);
    for (int trial = 0; trial < 50; ++trial) {
        TileSet a = TileSet::none(), b = TileSet::none();
        std::set<int> sa, sb;
        for (int i = 0; i < grid.count(); ++i) {
            if (coin(rng)) {
                a.addOverlapping(grid, grid.tile(i));
                sa.insert(i);
            }
            if (coin(rng)) {
                b.addOverlapping(grid, grid.tile(i));
                sb.insert(i);
            }
        }
        std::set<int> either = sa;
        either.insert(sb.begin(), sb.end());
        EXPECT_EQ(members(a.unite(b), grid), either);
        EXPECT_EQ(members(a.unite(TileSet::none()), grid), sa);
        EXPECT_TRUE(a.unite(TileSet()).every());
        EXPECT_TRUE(TileSet().unite(b).every());
    }
    EXPECT_TRUE(TileSet().every());
    EXPECT_EQ(TileSet().size(grid), grid.count());
    EXPECT_TRUE(TileSet::none().empty());
}

// A set grown onto another grid (a film's tiles onto a larger, offset grid of the same tile size, as
// deep tiles go from the film to a fragment set's grid): a tile of it is a member exactly when it shares
// a pixel with some member tile grown by the margin, by testing every pair.
TEST(TileSet, GrownMatchesTestingEveryPair) {
    const TileGrid film(70, 40, 8), band(-13, -13, 96, 66, 8);
    std::mt19937 rng(11);
    std::bernoulli_distribution coin(0.1);
    for (int trial = 0; trial < 30; ++trial) {
        TileSet a = TileSet::none();
        for (int i = 0; i < film.count(); ++i)
            if (coin(rng)) a.addOverlapping(film, film.tile(i));
        const int margin = trial % 7 * 3;
        std::set<int> expected;
        for (int j = 0; j < band.count(); ++j)
            for (int i = 0; i < film.count(); ++i) {
                const PixelBounds t = film.tile(i);
                if (a.contains(i) &&
                    band.tile(j).overlaps(PixelBounds::corners(t.x0 - margin, t.y0 - margin, t.x1 + margin, t.y1 + margin)))
                    expected.insert(j);
            }
        EXPECT_EQ(members(a.grown(film, margin, band), band), expected) << trial;
    }
    EXPECT_TRUE(TileSet().grown(film, 4, band).every());
    EXPECT_TRUE(TileSet::none().grown(film, 4, band).empty());
}

}  // namespace clipblur
