#include "renderer/clipped/frame_fragments.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/geometry/convex_polygon.h"
#include "renderer/propagation/surface_path.h"
#include "renderer/test_scenes.h"
#include "support/test_frame.h"

namespace clipblur {

namespace {

using test::rasterQuad;

// Area of triangle `t` (raster) inside the pixel square at (x, y), by clipping to its four sides.
double areaInPixel(const std::array<glm::dvec2, 3>& t, int x, int y) {
    ConvexPolygon p = ConvexPolygon::triangle(t[0], t[1], t[2]);
    if (p.area() < 0.0) p = ConvexPolygon::triangle(t[0], t[2], t[1]);
    const glm::dvec2 c[4] = {{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}};
    for (int k = 0; k < 4 && !p.degenerate(); ++k) {
        ConvexPolygon in;
        clipByLine(p, c[k], c[(k + 1) % 4], in);
        p = in;
    }
    return p.degenerate() ? 0.0 : p.area();
}

}  // namespace

// A wall over the whole 32x32 film at depth 6 (its diagonal along x = y, on pixel corners) and a small
// quad in front of it over [19.5, 22.5) x [2.5, 4.5), inside the 8 px tile [16, 24) x [0, 8). The frame's
// fragment triangles, projected again at the frame's time, must cover every pixel exactly once (the
// wall is everywhere), and the partly hidden tile must hold its wall as rectangles, not a pair of
// triangles per pixel.
TEST(FrameFragments, PartlyHiddenWallIsCutIntoRectanglesThatTileEachPixel) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(rasterQuad(-32.0, -32.0, 64.0, 64.0, 6.0));
    job.scene.objects.push_back(rasterQuad(19.5, 2.5, 22.5, 4.5, 3.0));
    const test::TestFrame frame(job.scene, 0.0, 1.0, 8);
    FrameFragmentStats stats;
    const std::vector<FragmentTriangle> triangles = buildFrameFragments(frame.setup(), {.time = 0.0}, nullptr, stats);
    const MotionSnapshot at(job.scene, frame.setup().projection, 0.0);

    std::vector<double> covered(32 * 32, 0.0);
    for (const FragmentTriangle& t : triangles) {
        std::array<glm::dvec2, 3> raster;
        for (int k = 0; k < 3; ++k) raster[k] = project(at, job.scene, {t.object, t.triangle, t.bary[k]}).raster;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) covered[static_cast<std::size_t>(y * 32 + x)] += areaInPixel(raster, x, y);
    }
    // Projection and clipping round at 1e-13 px^2 per piece; a missing or doubled piece is 1e-3 or more.
    for (int i = 0; i < 32 * 32; ++i) EXPECT_NEAR(covered[static_cast<std::size_t>(i)], 1.0, 1e-9) << "pixel " << i;

    // Tiles the quad does not reach keep each wall triangle's part whole: two fragment triangles per
    // tile (a square, or on the diagonal two halves), 30 over 15 tiles; the quad is whole in its tile
    // (2). The wall there: rows 0-1 and 5-7 of whole pixels are two rectangles, rows 2-4 hold the runs
    // [16, 19) and [23, 24), two more: 8 triangles. Rows 2-4, columns 19-22 are 12 pixels partly
    // hidden, kept per pixel: their wall pieces are convex parts of the pixel minus the quad, at most 3
    // per pixel fanned into at most 2 triangles each. Cut per pixel, the set was 132.
    EXPECT_GE(stats.triangles, 30 + 2 + 8 + 12);
    EXPECT_LE(stats.triangles, 30 + 2 + 8 + 12 * 6);
}

}  // namespace clipblur
