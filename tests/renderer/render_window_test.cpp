#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/job_loader.h"
#include "io/shard.h"
#include "renderer/render.h"
#include "scene/error.h"

namespace clipblur {

namespace {

// configs/default.yaml (a ball flying across a textured floor, a spinning box, a panning camera, every
// AOV) at an odd size whose 32-pixel render tiles do not line up with any shard border.
// "clipped_sweep" is clipped with sweep integration, whose fragments leave part of their coverage in other
// tiles' pixels: a shard must also re-clip the tiles next to it.
RenderJob smallMovingJob(const std::string& method) {
    const bool sweep = method == "clipped_sweep";
    return loadJob(std::string(CLIPBLUR_SOURCE_DIR) + "/configs/default.yaml",
                   {"film.width=67", "film.height=41", "render.method=" + std::string(sweep ? "clipped" : method),
                    "render.samples=3", "render.max_subframes=2", "render.audit=true",
                    std::string("render.time_integration=") + (sweep ? "sweep" : "subframes")});
}

// Every channel of `part` equals the same pixels of `whole` bit for bit (memcmp, so NaN and the
// infinite depth of background pixels compare too).
void expectSamePixels(const Image& whole, const Image& part, const std::string& what) {
    ASSERT_EQ(part.channels.size(), whole.channels.size()) << what;
    for (std::size_t c = 0; c < whole.channels.size(); ++c) {
        ASSERT_EQ(part.channels[c].name, whole.channels[c].name) << what;
        ASSERT_EQ(part.channels[c].values.size(), part.window.area());
        int differing = 0;
        for (int y = part.window.y0; y < part.window.y1; ++y)
            for (int x = part.window.x0; x < part.window.x1; ++x)
                differing += std::memcmp(&part.channels[c].values[part.index(x, y)],
                                         &whole.channels[c].values[whole.index(x, y)], sizeof(float)) != 0;
        EXPECT_EQ(differing, 0) << what << " channel " << whole.channels[c].name;
    }
}

}  // namespace

TEST(RenderWindow, DefaultIsTheWholeFilm) {
    RenderJob job = smallMovingJob("stochastic");
    EXPECT_EQ(renderWindow(job), PixelBounds::sized(0, 0, 67, 41));
    job.render.window = PixelBounds::sized(5, 6, 7, 8);
    EXPECT_EQ(renderWindow(job), PixelBounds::sized(5, 6, 7, 8));
}

TEST(RenderWindow, WindowOutsideTheFilmIsARenderError) {
    RenderJob job = smallMovingJob("stochastic");
    for (const PixelBounds w : {PixelBounds::sized(0, 0, 0, 5), PixelBounds::sized(-1, 0, 5, 5), PixelBounds::sized(60, 0, 8, 5),
                               PixelBounds::sized(0, 40, 5, 2)}) {
        job.render.window = w;
        try {
            renderFrame(job, 0);
            ADD_FAILURE() << "accepted " << toString(w);
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::Render) << toString(w);
        }
    }
}

// A window render is the whole render's pixels in that window, bit for bit, and carries the window as
// its data window. Shard windows of 3 (bands) and 4 (2 x 2) shards cut through render tiles. The whole
// render is audited; shards whose every pixel equals it need not be (the audit was 60 % of their time).
class WindowedMethod : public ::testing::TestWithParam<std::string> {};

TEST_P(WindowedMethod, ShardWindowsEqualTheWholeRender) {
    RenderJob job = smallMovingJob(GetParam());
    const Image whole = renderFrame(job, 0).image;
    ASSERT_EQ(whole.window, PixelBounds::sized(0, 0, 67, 41));
    job.render.audit = false;
    for (const int count : {3, 4}) {
        for (int index = 0; index < count; ++index) {
            const PixelBounds w = shardWindow(67, 41, {index, count});
            job.render.window = w;
            const Image part = renderFrame(job, 0).image;
            EXPECT_EQ(part.width, 67);
            EXPECT_EQ(part.height, 41);
            EXPECT_EQ(part.window, w);
            expectSamePixels(whole, part, GetParam() + " shard " + std::to_string(index) + "/" + std::to_string(count));
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, WindowedMethod, ::testing::Values("stochastic", "clipped", "clipped_sweep", "accumulation"),
                         [](const auto& info) { return info.param; });

}  // namespace clipblur
