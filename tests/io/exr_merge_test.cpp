#include <cstring>

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "io/exr_merge.h"
#include "io/shard.h"
#include "scene/error.h"
#include "tests/support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

// Frame layout used throughout: R, G, B, A stored as half and Z as float, so one file mixes types.
static const std::vector<std::string> kChannels{"R", "G", "B", "A", "Z"};
constexpr std::size_t kPixelBytes = 4 * sizeof(Imath::half) + sizeof(float);

// Half channels get bit patterns a float round trip would change: a NaN with a payload, a negative zero,
// a subnormal; Z gets a float no half can hold. Each depends on (x, y, c) so misplaced copies show.
static std::uint16_t halfBits(int x, int y, int c) {
    switch ((x + 3 * y + c) % 5) {
        case 0: return 0x7e01 + static_cast<std::uint16_t>(x % 64);  // quiet NaN, payload x
        case 1: return 0x8000;                                       // -0
        case 2: return 0x0001 + static_cast<std::uint16_t>(y);       // subnormal
        default: return static_cast<std::uint16_t>(0x3c00 + x * 7 + y * 131 + c);
    }
}
static float depth(int x, int y) { return 1.0f + 0.1f * static_cast<float>(x) + 1e-5f * static_cast<float>(y); }

static void packPixel(std::byte* dst, int x, int y) {
    for (int c = 0; c < 4; ++c) {
        const std::uint16_t bits = halfBits(x, y, c);
        std::memcpy(dst + c * 2, &bits, 2);
    }
    const float z = depth(x, y);
    std::memcpy(dst + 8, &z, 4);
}

static void writeShard(const std::string& framePath, int width, int height, TileShard shard, const std::string& hash) {
    const PixelBounds w = shardWindow(width, height, shard);
    OIIO::ImageSpec spec(w.width(), w.height(), 5, OIIO::TypeDesc::HALF);
    spec.channelformats = {OIIO::TypeHalf, OIIO::TypeHalf, OIIO::TypeHalf, OIIO::TypeHalf, OIIO::TypeFloat};
    spec.channelnames = kChannels;
    spec.z_channel = 4;
    spec.x = w.x0;
    spec.y = w.y0;
    spec.full_width = width;
    spec.full_height = height;
    spec.attribute(std::string(kConfigHashKey), hash);
    spec.attribute(std::string(kTileIndexKey), shard.index);
    spec.attribute(std::string(kTileCountKey), shard.count);
    spec.attribute("clipblur:method", "stochastic");
    std::vector<std::byte> pixels(kPixelBytes * static_cast<std::size_t>(w.width() * w.height()));
    for (int y = 0; y < w.height(); ++y)
        for (int x = 0; x < w.width(); ++x)
            packPixel(pixels.data() + kPixelBytes * static_cast<std::size_t>(y * w.width() + x), w.x0 + x, w.y0 + y);
    const std::string path = shardPath(framePath, shard);
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeUnknown, pixels.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

class ExrMerge : public ::testing::Test {
protected:
    void SetUp() override {
        dir = testing::freshTempDir("clipblur_merge_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        frame = (dir / "out.0007.exr").string();
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
    std::string frame;
};

TEST_F(ExrMerge, CopiesStoredBitsIntoFullWindow) {
    const int width = 37, height = 23, count = 6;  // neither side divides evenly
    for (int i = 0; i < count; ++i) writeShard(frame, width, height, {i, count}, "cafe");
    mergeShards(frame, count);

    auto in = OIIO::ImageInput::open(frame);
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.x, 0);
    EXPECT_EQ(spec.y, 0);
    EXPECT_EQ(spec.width, width);
    EXPECT_EQ(spec.height, height);
    EXPECT_EQ(spec.full_width, width);
    EXPECT_EQ(spec.full_height, height);
    ASSERT_EQ(spec.channelnames, kChannels);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(spec.channelformat(c), OIIO::TypeHalf) << c;
    EXPECT_EQ(spec.channelformat(4), OIIO::TypeFloat);
    EXPECT_EQ(spec.get_string_attribute(std::string(kConfigHashKey)), "cafe");
    EXPECT_EQ(spec.get_string_attribute("clipblur:method"), "stochastic");
    EXPECT_EQ(spec.find_attribute(std::string(kTileIndexKey)), nullptr);
    EXPECT_EQ(spec.find_attribute(std::string(kTileCountKey)), nullptr);

    ASSERT_EQ(spec.pixel_bytes(true), kPixelBytes);
    std::vector<std::byte> got(spec.image_bytes(true)), want(got.size());
    ASSERT_TRUE(in->read_image(0, 0, 0, 5, OIIO::TypeUnknown, got.data()));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            packPixel(want.data() + kPixelBytes * static_cast<std::size_t>(y * width + x), x, y);
    EXPECT_EQ(std::memcmp(got.data(), want.data(), got.size()), 0);
}

TEST_F(ExrMerge, SingleShardRoundTrips) {
    writeShard(frame, 5, 4, {0, 1}, "h");
    mergeShards(frame, 1);
    ImageExpectation full{5, 4, PixelBounds::sized(0, 0, 5, 4), "h", kChannels};
    EXPECT_TRUE(checkImage(frame, full).complete);
}

TEST_F(ExrMerge, ReportsEveryIncompleteShardAndWritesNothing) {
    const int width = 32, height = 16, count = 8;
    for (int i = 0; i < count; ++i)
        if (i != 2) writeShard(frame, width, height, {i, count}, "h1");
    const std::string cut = shardPath(frame, {4, count});
    fs::resize_file(cut, fs::file_size(cut) / 2);
    writeShard(frame, width, height, {6, count}, "stale");  // rendered from an older config

    const ShardSetCheck check = checkShards(frame, count);
    EXPECT_EQ(check.resolved.config_hash, "h1");  // from shard 0, the first that opens
    EXPECT_EQ(check.resolved.width, width);
    EXPECT_EQ(check.incomplete, (std::vector<int>{2, 4, 6}));
    ASSERT_EQ(check.reasons.size(), 3u);

    try {
        mergeShards(frame, count);
        FAIL() << "merge of incomplete shards succeeded";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Output);
        for (int i : {2, 4, 6}) EXPECT_NE(e.message().find(shardPath(frame, {i, count})), std::string::npos) << e.message();
    }
    EXPECT_FALSE(fs::exists(frame));
}

TEST_F(ExrMerge, ExpectationFromJobOverridesShards) {
    for (int i = 0; i < 2; ++i) writeShard(frame, 8, 8, {i, 2}, "old");
    FrameExpectation job;
    job.config_hash = "new";
    EXPECT_EQ(checkShards(frame, 2, job).incomplete, (std::vector<int>{0, 1}));
    job.config_hash = "old";
    job.width = 9;  // display size from the job differs: every window is wrong
    job.height = 8;
    EXPECT_EQ(checkShards(frame, 2, job).incomplete, (std::vector<int>{0, 1}));
    job.width = 8;
    EXPECT_TRUE(checkShards(frame, 2, job).complete());
}

TEST_F(ExrMerge, NoShardsAtAllAreAllMissing) {
    const ShardSetCheck check = checkShards(frame, 3);
    EXPECT_EQ(check.incomplete, (std::vector<int>{0, 1, 2}));
}

}  // namespace clipblur
