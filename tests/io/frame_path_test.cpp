#include <filesystem>
#include <fstream>
#include <string_view>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/frame_path.h"
#include "io/stats_writer.h"
#include "scene/error.h"
#include "tests/support/cli_harness.h"

namespace clipblur {

TEST(FramePath, HashRunsBecomeZeroPaddedFrames) {
    EXPECT_EQ(framePath("shot.####.exr", 12), "shot.0012.exr");
    EXPECT_EQ(framePath("shot.#.exr", 123), "shot.123.exr");
    EXPECT_EQ(framePath("a##/b####.exr", 7), "a07/b0007.exr");
    EXPECT_EQ(framePath("f.###.exr", -4), "f.-004.exr");
    EXPECT_EQ(framePath("plain.exr", 3), "plain.exr");
}

TEST(FramePath, SeveralFramesNeedAPattern) {
    EXPECT_EQ(outputPathForFrame("one.exr", 5, 5, 5), "one.exr");
    EXPECT_EQ(outputPathForFrame("s.##.exr", 6, 5, 9), "s.06.exr");
    try {
        outputPathForFrame("one.exr", 5, 5, 9);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Usage);
    }
}

TEST(FramePath, StatsSitBesideTheImage) {
    EXPECT_EQ(defaultStatsPath("out/shot.0012.exr"), "out/shot.0012.stats.json");
}

TEST(FramePath, RangesMayBeNegative) {
    const auto range = [](std::string_view text) {
        const FrameRange r = parseFrameRange(text);
        return std::pair(r.first, r.last);
    };
    EXPECT_EQ(range("7"), std::pair(7, 7));
    EXPECT_EQ(range("1-24"), std::pair(1, 24));
    EXPECT_EQ(range("-3--1"), std::pair(-3, -1));
    EXPECT_EQ(range("-2-5"), std::pair(-2, 5));
    EXPECT_EQ(range("-4"), std::pair(-4, -4));
    for (const char* bad : {"", "a", "1-", "-", "3-1", "1-2-3", " 1", "1..2", "99999999999"}) {
        try {
            parseFrameRange(bad);
            ADD_FAILURE() << "accepted \"" << bad << "\"";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::Usage) << bad;
        }
    }
}

// Issue 24, kind 3: --frames skipped the job's frame limits, and 2147483647 overflowed the frame loop.
TEST(FramePath, RangesKeepTheJobsFrameLimits) {
    EXPECT_EQ(parseFrameRange("-1000000").first, -1000000);
    EXPECT_EQ(parseFrameRange("1000000").last, 1000000);
    EXPECT_EQ(parseFrameRange("1-1000000").last, 1000000);
    for (const char* bad : {"2147483647", "0-2147483647", "2147483646-2147483647", "-2147483648", "1000001",
                            "-1000001--1000000", "0-1000000", "-500000-500000"}) {
        try {
            parseFrameRange(bad);
            ADD_FAILURE() << "accepted \"" << bad << "\"";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::Usage) << bad;
            EXPECT_NE(e.message().find("1000000"), std::string::npos) << e.what();
        }
    }
}

TEST(StatsWriter, WritesCountsTimingsAndPeakMemory) {
    RenderStats stats;
    StochasticStats stochastic;
    stochastic.render_seconds = 0.5;
    stochastic.primary_rays = 1000;
    stochastic.shadow_rays = 234;
    stats.method = stochastic;
    stats.warnings = {"one", "two"};
    stats.reference = RenderStats::Reference{"ref.exr", 0.25, 0.5, 0.125};
    const auto path = testing::freshTempDir("clipblur_stats_test") / "s.json";
    // 1e9 s after the epoch is 2001-09-09 01:46:40 UTC (a well-known timestamp).
    const StatsContext context{3, "x.exr", 2, "0123456789abcdef",
                               utcTimestamp(std::chrono::system_clock::from_time_t(1000000000))};
    writeStats(path, statsToJson(stats, context));
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("frame"), 3);
    EXPECT_EQ(j.at("threads"), 2);
    EXPECT_EQ(j.at("config_hash"), "0123456789abcdef");
    EXPECT_EQ(j.at("start_time"), "2001-09-09T01:46:40Z");
    EXPECT_EQ(j.at("counts").at("rays"), 1234) << "primary plus shadow rays";
    EXPECT_EQ(j.at("counts").at("primary_rays"), 1000);
    EXPECT_EQ(j.at("seconds").at("render"), 0.5);
    EXPECT_EQ(j.at("info").at("method"), "stochastic");
    EXPECT_EQ(j.at("info").at("warning"), "one; two");
    EXPECT_EQ(j.at("info").at("reference"), "ref.exr");
    EXPECT_EQ(j.at("error").at("rmse"), 0.25);
    EXPECT_EQ(j.at("error").at("mean_abs"), 0.125);
    EXPECT_FALSE(j.at("counts").contains("subframes_total")) << "only the method's own fields";
    EXPECT_GT(j.at("peak_memory_bytes").get<long long>(), 1 << 20);  // this process holds more than 1 MiB
}

TEST(StatsWriter, WritesMeasuredValuesOfTheirOwn) {
    RenderStats stats;
    ClippedStats clipped;
    clipped.estimated_error = 0.125;
    stats.method = clipped;
    const nlohmann::json j = statsToJson(stats, StatsContext{0, "x.exr", 1, "0", "now"});
    EXPECT_EQ(j.at("values").at("estimated_error"), 0.125);
    EXPECT_FALSE(j.at("counts").contains("estimated_error")) << "a real number, not a count";
}

}  // namespace clipblur
