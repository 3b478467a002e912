#include <fstream>
#include <random>
#include <set>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "io/shard.h"
#include "scene/error.h"
#include "tests/support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

static ExitCode codeOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.code();
    }
    return ExitCode::Ok;
}

TEST(Shard, ParseAcceptsIndexBelowCount) {
    EXPECT_EQ(parseTileShard("3/8"), (TileShard{3, 8}));
    EXPECT_EQ(parseTileShard("0/1"), (TileShard{0, 1}));
}

TEST(Shard, ParseRejectsMalformedAndOutOfRangeAsUsage) {
    for (const char* bad : {"8/8", "-1/4", "1/0", "0/-2", "a/b", "1", "", "/", "1/2x", " 1/2", "1/2/3"})
        EXPECT_EQ(codeOf([&] { parseTileShard(bad); }), ExitCode::Usage) << bad;
}

TEST(Shard, GridPicksSquarestBlocks) {
    // 64x48, 8 shards: 4x2 gives 16x24 blocks (|ln(2/3)| = 0.41), 2x4 gives 32x12 (0.98), 8x1 8x48, 1x8 64x6.
    const ShardGrid g8 = shardGrid(64, 48, 8);
    EXPECT_EQ(g8.cols, 4);
    EXPECT_EQ(g8.rows, 2);
    const ShardGrid g4 = shardGrid(64, 48, 4);
    EXPECT_EQ(g4.cols, 2);
    EXPECT_EQ(g4.rows, 2);
    // A prime count has only bands; vertical 9.1x48 (|ln| 1.66) beats horizontal 64x6.9 (2.23).
    const ShardGrid g7 = shardGrid(64, 48, 7);
    EXPECT_EQ(g7.cols, 7);
    EXPECT_EQ(g7.rows, 1);
    // Too narrow for 7 columns: horizontal bands are the only grid without empty shards.
    const ShardGrid thin = shardGrid(3, 100, 7);
    EXPECT_EQ(thin.cols, 1);
    EXPECT_EQ(thin.rows, 7);
}

TEST(Shard, WindowsOfUnevenFrameByHand) {
    // 10x7 in 2x2 blocks: columns split at floor(10/2) = 5, rows at floor(7/2) = 3.
    EXPECT_EQ(shardWindow(10, 7, {0, 4}), PixelBounds::sized(0, 0, 5, 3));
    EXPECT_EQ(shardWindow(10, 7, {1, 4}), PixelBounds::sized(5, 0, 5, 3));
    EXPECT_EQ(shardWindow(10, 7, {2, 4}), PixelBounds::sized(0, 3, 5, 4));
    EXPECT_EQ(shardWindow(10, 7, {3, 4}), PixelBounds::sized(5, 3, 5, 4));
    EXPECT_EQ(shardWindow(10, 7, {0, 1}), PixelBounds::sized(0, 0, 10, 7));
}

TEST(Shard, TooManyTilesIsUsageError) {
    EXPECT_EQ(codeOf([] { shardWindow(2, 2, {0, 5}); }), ExitCode::Usage);  // 5 is prime and > 2
    EXPECT_EQ(codeOf([] { shardWindow(4, 4, {0, 17}); }), ExitCode::Usage);
    EXPECT_EQ(codeOf([] { shardWindow(0, 4, {0, 1}); }), ExitCode::Usage);
    EXPECT_EQ(codeOf([] { shardWindow(4, 4, {4, 4}); }), ExitCode::Usage);
}

// Seeded random sizes and counts: every pixel lies in exactly one shard, no shard is empty, and blocks in
// a grid row/column differ by at most one pixel (the floor split).
TEST(Shard, RandomWindowsPartitionTheFrame) {
    std::mt19937 rng(20040101);
    std::uniform_int_distribution<int> size(1, 90), tiles(1, 40);
    int tested = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const int w = size(rng), h = size(rng), n = tiles(rng);
        bool fits = false;  // independent test for whether any cols x rows grid has no empty block
        for (int c = 1; c <= n; ++c)
            if (n % c == 0 && c <= w && n / c <= h) fits = true;
        if (!fits) {
            EXPECT_EQ(codeOf([&] { shardWindow(w, h, {0, n}); }), ExitCode::Usage) << w << "x" << h << " " << n;
            continue;
        }
        ++tested;
        std::vector<int> cover(static_cast<std::size_t>(w * h), 0);
        std::set<int> widths, heights;
        for (int i = 0; i < n; ++i) {
            const PixelBounds d = shardWindow(w, h, {i, n});
            ASSERT_FALSE(d.empty());
            ASSERT_GE(d.x0, 0);
            ASSERT_GE(d.y0, 0);
            ASSERT_LE(d.x0 + d.width(), w);
            ASSERT_LE(d.y0 + d.height(), h);
            widths.insert(d.width());
            heights.insert(d.height());
            for (int y = d.y0; y < d.y0 + d.height(); ++y)
                for (int x = d.x0; x < d.x0 + d.width(); ++x) ++cover[static_cast<std::size_t>(y * w + x)];
        }
        for (int c : cover) ASSERT_EQ(c, 1) << w << "x" << h << " " << n;
        EXPECT_LE(*widths.rbegin() - *widths.begin(), 1);
        EXPECT_LE(*heights.rbegin() - *heights.begin(), 1);
    }
    EXPECT_GT(tested, 200);  // the random draw must exercise mostly valid layouts
}

TEST(Shard, PathTagGoesBeforeExtension) {
    EXPECT_EQ(shardPath("out.0001.exr", {3, 8}), "out.0001.tile-3-of-8.exr");
    EXPECT_EQ(shardPath("/a.b/frames/x.exr", {0, 2}), "/a.b/frames/x.tile-0-of-2.exr");
    EXPECT_EQ(shardPath("/a.b/noext", {1, 2}), "/a.b/noext.tile-1-of-2");
}

// A small EXR written directly with OpenImageIO, independent of the project's image writer.
static void writeShard(const fs::path& path, int width, int height, const PixelBounds& w, const std::string& hash,
                       const std::vector<std::string>& channels = {"R", "G", "B", "A"}) {
    OIIO::ImageSpec spec(w.width(), w.height(), static_cast<int>(channels.size()), OIIO::TypeDesc::HALF);
    spec.x = w.x0;
    spec.y = w.y0;
    spec.full_x = 0;
    spec.full_y = 0;
    spec.full_width = width;
    spec.full_height = height;
    spec.channelnames = channels;
    spec.attribute(std::string(kConfigHashKey), hash);
    std::vector<float> pixels(static_cast<std::size_t>(w.width() * w.height()) * channels.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<float>(i % 97) / 8.0f;
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path.string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeFloat, pixels.data()));
    ASSERT_TRUE(out->close());
}

class ShardCheck : public ::testing::Test {
protected:
    void SetUp() override {
        // One folder per test: ctest runs the tests of this fixture in parallel processes.
        dir = testing::freshTempDir(std::string("clipblur_shard_test_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
};

TEST_F(ShardCheck, AcceptsMatchingShardAndRejectsEachMismatch) {
    const TileShard shard{2, 4};
    const PixelBounds w = shardWindow(40, 30, shard);
    const fs::path good = dir / "good.exr";
    writeShard(good, 40, 30, w, "abc");
    EXPECT_TRUE(shardIsComplete(
        good, {.width = 40, .height = 30, .shard = shard, .config_hash = "abc", .channels = {"R", "G", "B", "A"}}));
    EXPECT_TRUE(shardIsComplete(good, {.width = 40, .height = 30, .shard = shard}));  // hash not checked when not known

    EXPECT_FALSE(shardIsComplete(good, {.width = 40, .height = 30, .shard = shard, .config_hash = "abd"}));
    EXPECT_FALSE(shardIsComplete(good, {.width = 40, .height = 30, .shard = {1, 4}, .config_hash = "abc"}));   // another shard's window
    EXPECT_FALSE(shardIsComplete(good, {.width = 40, .height = 31, .shard = shard, .config_hash = "abc"}));    // another display window
    EXPECT_FALSE(shardIsComplete(good, {.width = 40, .height = 30, .shard = shard, .config_hash = "abc", .channels = {"R", "G", "B", "A", "Z"}}));
    EXPECT_FALSE(shardIsComplete(dir / "absent.exr", {.width = 40, .height = 30, .shard = shard, .config_hash = "abc"}));

    ImageExpectation e{40, 30, w, "zzz", {}};
    const ImageCheck c = checkImage(good, e);
    EXPECT_FALSE(c.complete);
    EXPECT_NE(c.reason.find("config hash"), std::string::npos) << c.reason;
}

TEST_F(ShardCheck, TruncatedOrForeignFileIsIncomplete) {
    const TileShard shard{0, 1};
    const PixelBounds w = PixelBounds::sized(0, 0, 64, 64);
    const fs::path good = dir / "full.exr";
    writeShard(good, 64, 64, w, "h", {"R", "G", "B", "A", "Z", "coverage"});
    ASSERT_TRUE(shardIsComplete(good, {.width = 64, .height = 64, .shard = shard, .config_hash = "h"}));

    // Keep the header and part of the pixel chunks, as a node dying mid-copy would.
    const auto size = fs::file_size(good);
    for (double keep : {0.5, 0.9}) {
        const fs::path cut = dir / "cut.exr";
        fs::copy_file(good, cut, fs::copy_options::overwrite_existing);
        fs::resize_file(cut, static_cast<std::uintmax_t>(static_cast<double>(size) * keep));
        EXPECT_FALSE(shardIsComplete(cut, {.width = 64, .height = 64, .shard = shard, .config_hash = "h"})) << keep;
    }
    const fs::path text = dir / "text.exr";
    std::ofstream(text) << "not an image";
    EXPECT_FALSE(shardIsComplete(text, {.width = 64, .height = 64, .shard = shard, .config_hash = "h"}));
    fs::create_directories(dir / "folder.exr");
    EXPECT_FALSE(shardIsComplete(dir / "folder.exr", {.width = 64, .height = 64, .shard = shard, .config_hash = "h"}));
}

}  // namespace clipblur
