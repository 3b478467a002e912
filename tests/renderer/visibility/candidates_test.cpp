#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/render.h"
#include "renderer/visibility/candidates.h"
#include "renderer/visibility/embree_device.h"
#include "renderer/visibility/embree_scene.h"
#include "renderer/visibility/frame_geometry.h"
#include "tests/renderer/test_scenes.h"

namespace clipblur {

namespace {

// A wall over the whole 32 x 32 film at depth 20 and, in front of its left half, `stacked` quads over
// raster [1, 15] x [1, 31] at depths 5, 6, ...: only the nearest is visible, the rest are for rays to cull.
RenderJob wallWithStack(int stacked) {
    RenderJob job = test::squareFilmJob();
    job.render.method = Method::Clipped;
    job.scene.objects.push_back(test::rasterQuad(0, 0, 32, 32, 20.0));
    for (int k = 0; k < stacked; ++k) job.scene.objects.push_back(test::rasterQuad(1, 1, 15, 31, 5.0 + k));
    return job;
}

bool raysPayOffIn(const RenderJob& job, int tile_index, int rays_per_side) {
    const Projection projection(32, 32, job.scene.camera.vfov_degrees);
    const TileGrid grid(32, 32, job.render.tile_size);
    const FrameGeometry frame(job.scene, projection, 0.0, grid);
    return raysPayOff(frame, frame.tileTriangles(tile_index), grid.tile(tile_index), rays_per_side);
}

}  // namespace

TEST(Candidates, RaysOnlyWhereThereIsSomethingToCull) {
    const RenderJob wall = wallWithStack(0), stack = wallWithStack(12);
    for (int tile = 0; tile < 16; ++tile) {  // 4 x 4 tiles of 8 px; column tile % 4, 0 and 1 the left half
        EXPECT_FALSE(raysPayOffIn(wall, tile, 2)) << tile;  // two triangles hiding nothing
        EXPECT_FALSE(raysPayOffIn(stack, tile, 0)) << tile;  // 0: never rays
        EXPECT_EQ(raysPayOffIn(stack, tile, 2), tile % 4 < 2) << tile;
    }
    // Rays cost n^2 per pixel: at 8 x 8 per pixel the same stack is cheaper to clip whole.
    EXPECT_FALSE(raysPayOffIn(stack, 0, 8));
    // Quads narrower than two ray spacings (1 px at 2 x 2) are candidates whatever the rays hit, so a
    // stack of them gives the rays nothing to cull; of quads 1.5 px wide it does.
    RenderJob slivers = wallWithStack(0);
    for (int k = 0; k < 40; ++k) slivers.scene.objects.push_back(test::rasterQuad(2, 1, 2.75, 7, 5.0 + k));
    EXPECT_FALSE(raysPayOffIn(slivers, 0, 2));
    RenderJob strips = wallWithStack(0);
    for (int k = 0; k < 40; ++k) strips.scene.objects.push_back(test::rasterQuad(2, 1, 3.5, 7, 5.0 + k));
    EXPECT_TRUE(raysPayOffIn(strips, 0, 2));
}

// Tiles whose rays would not pay hand the clipper every binned triangle; the others trace rays over
// themselves and a one-pixel border.
TEST(Candidates, RaysAreTracedOnlyOverTilesWhereTheyPay) {
    const RenderJob job = wallWithStack(12);
    const Projection projection(32, 32, job.scene.camera.vfov_degrees);
    const TileGrid grid(32, 32, job.render.tile_size);
    const FrameGeometry frame(job.scene, projection, 0.0, grid);
    const EmbreeDevice device;
    const EmbreeScene embree(device, job.scene, 0.0, 0.0);
    const MeshAdjacency adjacency(job.scene);
    CandidateScratch scratch;
    CandidateStats stats;
    std::vector<std::uint32_t> out;
    for (int tile = 0; tile < grid.count(); ++tile) {
        findCandidates(frame, embree, adjacency, projection, grid.tile(tile), tile, 2, scratch, out, stats);
        if (tile % 4 >= 2) EXPECT_EQ(out.size(), frame.tileTriangles(tile).size()) << tile;
    }
    EXPECT_EQ(stats.exhaustive_tiles, 8);
    EXPECT_EQ(stats.rays, 8 * 10 * 10 * 4);  // 8 tiles of 10 x 10 px with the border, 2 x 2 rays per pixel
    EXPECT_LT(stats.candidates, stats.binned);  // the stack's hidden quads are culled
}

// Where rays are skipped the clipper sees every binned triangle, the exact oracle, so the image is the
// one exhaustive candidates give in every tile.
TEST(Candidates, SkippingRaysWhereTheyDoNotPayChangesNoPixel) {
    RenderJob job = wallWithStack(12);
    job.render.visibility_rays = 2;
    const RenderResult mixed = renderFrame(job, 0);
    job.render.visibility_rays = 0;
    const RenderResult exhaustive = renderFrame(job, 0);
    EXPECT_GT(mixed.stats.counts.at("open_exhaustive_tiles"), 0);
    EXPECT_GT(mixed.stats.counts.at("open_rays"), 0);
    EXPECT_LT(mixed.stats.counts.at("open_candidates"), exhaustive.stats.counts.at("open_candidates"));
    for (std::size_t c = 0; c < mixed.image.channels.size(); ++c)
        EXPECT_EQ(mixed.image.channels[c].values, exhaustive.image.channels[c].values) << c;
}

}  // namespace clipblur
