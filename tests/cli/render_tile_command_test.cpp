#include <sys/stat.h>
#include <sys/wait.h>

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "io/shard.h"
#include "tests/support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 67;  // odd sizes: shard borders cut through the 32-pixel render tiles
constexpr int kHeight = 41;

int run(const std::string& command) {
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// configs/default.yaml (moving ball, spinning box, panning camera, every AOV, half output) made small.
std::string jobArgs(const std::string& method, const std::string& extra_sets = "") {
    return std::string(CLIPBLUR_SOURCE_DIR) + "/configs/default.yaml --set film.width=" + std::to_string(kWidth) +
           " --set film.height=" + std::to_string(kHeight) + " --set render.method=" + method +
           " --set render.samples=3 --set render.max_subframes=2 --set output.png_preview=false" + extra_sets;
}

// Runs `clipblur ARGS`, stdout to dir/stdout.txt; returns the exit code.
int clipblur(const fs::path& dir, const std::string& args) {
    return run(std::string(CLIPBLUR_BINARY) + " " + args + " > " + (dir / "stdout.txt").string() + " 2> " +
               (dir / "stderr.txt").string());
}

int renderShard(const fs::path& dir, const std::string& method, const fs::path& frame, TileShard shard,
                const std::string& extra_sets = "") {
    return clipblur(dir, "render " + jobArgs(method, extra_sets) + " --progress none --threads 2 --out " +
                             frame.string() + " --tile " + std::to_string(shard.index) + "/" +
                             std::to_string(shard.count));
}

struct StoredImage {
    OIIO::ImageSpec spec;
    std::vector<std::byte> pixels;  // as stored: half stays half
};

StoredImage readStored(const fs::path& path) {
    StoredImage image;
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        ADD_FAILURE() << "cannot open " << path << ": " << OIIO::geterror();
        return image;
    }
    image.spec = in->spec();
    image.pixels.resize(image.spec.image_bytes(true));
    EXPECT_TRUE(in->read_image(0, 0, 0, image.spec.nchannels, OIIO::TypeUnknown, image.pixels.data()))
        << in->geterror();
    return image;
}

// The merged frame has the whole render's windows, channels, stored types and pixel bits.
void expectSameFrame(const fs::path& whole_path, const fs::path& merged_path, const std::string& what) {
    const StoredImage whole = readStored(whole_path);
    const StoredImage merged = readStored(merged_path);
    EXPECT_EQ(merged.spec.full_width, kWidth) << what;
    EXPECT_EQ(merged.spec.full_height, kHeight) << what;
    EXPECT_EQ(merged.spec.x, 0) << what;
    EXPECT_EQ(merged.spec.y, 0) << what;
    EXPECT_EQ(merged.spec.width, kWidth) << what;
    EXPECT_EQ(merged.spec.height, kHeight) << what;
    EXPECT_EQ(merged.spec.channelnames, whole.spec.channelnames) << what;
    EXPECT_EQ(merged.spec.channelformats, whole.spec.channelformats) << what;
    EXPECT_EQ(merged.spec.format, whole.spec.format) << what;
    EXPECT_TRUE(merged.pixels == whole.pixels) << what << ": pixels differ";
}

ino_t inode(const fs::path& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 ? st.st_ino : 0;
}

}  // namespace

// Shards rendered one process each, merged by `clipblur merge`, equal one whole render bit for bit.
class RenderTileCommand : public ::testing::TestWithParam<std::string> {};

TEST_P(RenderTileCommand, MergedShardsEqualTheWholeRender) {
    const std::string method = GetParam();
    const fs::path dir = testing::freshTempDir("clipblur_cli_tiles_" + method);
    const fs::path whole = dir / "whole.exr";
    ASSERT_EQ(clipblur(dir, "render " + jobArgs(method) + " --progress none --threads 2 --out " + whole.string()), 0)
        << readText(dir / "stderr.txt");
    for (const int count : {1, 3, 4, 7}) {
        const fs::path frame = dir / ("n" + std::to_string(count)) / "frame.exr";
        for (int index = 0; index < count; ++index) {
            const TileShard shard{index, count};
            ASSERT_EQ(renderShard(dir, method, frame, shard), 0) << readText(dir / "stderr.txt");
            const fs::path shard_path = shardPath(frame.string(), shard);
            const StoredImage stored = readStored(shard_path);
            const PixelBounds w = shardWindow(kWidth, kHeight, shard);
            EXPECT_EQ(PixelBounds::sized(stored.spec.x, stored.spec.y, stored.spec.width, stored.spec.height), w);
            EXPECT_EQ(stored.spec.get_int_attribute(std::string(kTileIndexKey), -1), index);
            EXPECT_EQ(stored.spec.get_int_attribute(std::string(kTileCountKey), -1), count);
            EXPECT_TRUE(fs::exists(dir / frame.parent_path().filename() /
                                   ("frame.tile-" + std::to_string(index) + "-of-" + std::to_string(count) +
                                    ".stats.json")));
        }
        ASSERT_EQ(clipblur(dir, "merge " + jobArgs(method) + " --out " + frame.string() + " --tiles " +
                                    std::to_string(count)),
                  0)
            << readText(dir / "stderr.txt");
        expectSameFrame(whole, frame, method + " with " + std::to_string(count) + " shards");
    }
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Methods, RenderTileCommand, ::testing::Values("stochastic", "clipped"),
                         [](const auto& info) { return info.param; });

// A complete shard is skipped untouched; a truncated one, or one from another config, is rendered again.
TEST(RenderTileResume, OnlyIncompleteShardsAreRenderedAgain) {
    const fs::path dir = testing::freshTempDir("clipblur_cli_tiles_resume");
    const fs::path frame = dir / "frame.exr";
    const fs::path whole = dir / "whole.exr";
    ASSERT_EQ(clipblur(dir, "render " + jobArgs("stochastic") + " --progress none --out " + whole.string()), 0);
    for (int index = 0; index < 4; ++index) ASSERT_EQ(renderShard(dir, "stochastic", frame, {index, 4}), 0);

    const fs::path done = shardPath(frame.string(), {0, 4});
    const ino_t done_inode = inode(done);
    ASSERT_EQ(renderShard(dir, "stochastic", frame, {0, 4}), 0);
    EXPECT_NE(readText(dir / "stdout.txt").find("complete, skipped"), std::string::npos) << readText(dir / "stdout.txt");
    // Written atomically by rename, so a re-render would show as a new inode.
    EXPECT_EQ(inode(done), done_inode);

    // A node that died while copying: the header survives, the pixel chunks do not.
    const fs::path cut = shardPath(frame.string(), {1, 4});
    fs::resize_file(cut, fs::file_size(cut) / 2);
    EXPECT_FALSE(shardIsComplete(cut, {.width = kWidth, .height = kHeight, .shard = {1, 4}}));
    ASSERT_EQ(renderShard(dir, "stochastic", frame, {1, 4}), 0);
    EXPECT_EQ(readText(dir / "stdout.txt").find("skipped"), std::string::npos);
    EXPECT_TRUE(shardIsComplete(cut, {.width = kWidth, .height = kHeight, .shard = {1, 4}}));

    // Another seed is another config hash: that shard must not be mixed into this job's frame.
    ASSERT_EQ(renderShard(dir, "stochastic", frame, {2, 4}, " --set render.seed=99"), 0);
    EXPECT_NE(clipblur(dir, "merge " + jobArgs("stochastic") + " --out " + frame.string() + " --tiles 4 --check"), 0);
    EXPECT_NE(readText(dir / "stdout.txt").find("tile-2-of-4"), std::string::npos) << readText(dir / "stdout.txt");
    ASSERT_EQ(renderShard(dir, "stochastic", frame, {2, 4}), 0);
    EXPECT_EQ(readText(dir / "stdout.txt").find("skipped"), std::string::npos);

    ASSERT_EQ(clipblur(dir, "merge " + jobArgs("stochastic") + " --out " + frame.string() + " --tiles 4"), 0)
        << readText(dir / "stderr.txt");
    expectSameFrame(whole, frame, "resumed shards");
    fs::remove_all(dir);
}

}  // namespace clipblur
