#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "io/job_loader.h"
#include "renderer/render.h"

namespace clipblur {

// docs/stability.md: a camera dollying through posts. Geometry crossing the camera plane is clipped in
// 3D (never projected through the eye), its image speed is unbounded so the subframe plan hits the cap,
// and the render says so in a warning instead of failing or producing non-finite pixels. The fragment
// audit checks every tile on the way.
TEST(FailureModes, NearPlaneCrossingIsClippedAndWarned) {
    const RenderJob job = loadJob(std::string(CLIPBLUR_SOURCE_DIR) + "/configs/bench/near_plane.yaml",
                                  {"film.width=48", "film.height=27", "render.max_subframes=12", "render.audit=true"});
    const RenderResult r = renderFrame(job, 0);
    EXPECT_GT(r.stats.clipped().reclip.near_clipped + r.stats.clipped().near_crossing_fragments, 0);
    EXPECT_GT(r.stats.clipped().capped_tiles, 0);
    ASSERT_FALSE(r.stats.warnings.empty());
    EXPECT_NE(r.stats.warnings.back().find("max_subframes"), std::string::npos) << "the capped tiles' warning comes last";
    for (std::size_t c = 0; c < 4; ++c) {
        for (float v : r.image.channels[c].values) {
            ASSERT_TRUE(std::isfinite(v));
            ASSERT_GE(v, 0.0f);
            if (c == 3) {
                ASSERT_LE(v, 1.0f + 1e-6f);  // coverage
            }
        }
    }
}

}  // namespace clipblur
