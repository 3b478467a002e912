#include "io/shard.h"

#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>

#include "io/image_files.h"
#include "scene/error.h"

namespace clipblur {

namespace fs = std::filesystem;

static bool parseInt(std::string_view text, int& value) {
    if (text.empty()) return false;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end;
}

TileShard parseTileShard(std::string_view text) {
    const auto usage = [&](const std::string& why) {
        return Error(ExitCode::Usage, "bad tile \"" + std::string(text) + "\": " + why + " (expected I/N with 0 <= I < N)");
    };
    const std::size_t slash = text.find('/');
    if (slash == std::string_view::npos) throw usage("no '/'");
    TileShard shard;
    const std::string counts = "1.." + std::to_string(kMaxShards);
    if (!parseInt(text.substr(0, slash), shard.index)) throw usage("index is not an integer");
    if (!parseInt(text.substr(slash + 1), shard.count)) throw usage("count is not an integer in " + counts);
    if (shard.count < 1 || shard.count > kMaxShards) throw usage("count must be in " + counts);
    if (shard.index < 0 || shard.index >= shard.count) throw usage("index out of range");
    return shard;
}

ShardGrid shardGrid(int width, int height, int count) {
    if (width < 1 || height < 1) throw Error(ExitCode::Usage, "cannot shard an empty frame");
    if (count < 1) throw Error(ExitCode::Usage, "tile count must be at least 1");
    ShardGrid best{0, 0};
    double bestSkew = std::numeric_limits<double>::infinity();
    for (int cols = 1; cols <= count; ++cols) {
        if (count % cols != 0) continue;
        const int rows = count / cols;
        if (cols > width || rows > height) continue;
        const double blockW = static_cast<double>(width) / cols;
        const double blockH = static_cast<double>(height) / rows;
        const double skew = std::abs(std::log(blockW / blockH));
        // Strictly better only, so ties keep fewer columns: longer scanlines per shard.
        if (skew < bestSkew) {
            bestSkew = skew;
            best = {cols, rows};
        }
    }
    if (best.cols == 0)
        throw Error(ExitCode::Usage, std::to_string(count) + " tiles do not fit a " + std::to_string(width) + "x" +
                                         std::to_string(height) + " frame without empty shards");
    return best;
}

// Split point k of n parts over [0, size): floor(k*size/n) in 64-bit so huge frames cannot overflow.
static int splitPoint(int k, int n, int size) {
    return static_cast<int>(static_cast<long long>(k) * size / n);
}

PixelBounds shardWindow(int width, int height, TileShard shard) {
    if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count)
        throw Error(ExitCode::Usage, "tile " + std::to_string(shard.index) + "/" + std::to_string(shard.count) +
                                         " out of range");
    const ShardGrid grid = shardGrid(width, height, shard.count);
    const int col = shard.index % grid.cols;
    const int row = shard.index / grid.cols;
    return PixelBounds::corners(splitPoint(col, grid.cols, width), splitPoint(row, grid.rows, height),
                                splitPoint(col + 1, grid.cols, width), splitPoint(row + 1, grid.rows, height));
}

std::string shardPath(const std::string& framePath, TileShard shard) {
    const std::string tag = ".tile-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count);
    const fs::path p(framePath);
    if (!p.has_extension()) return framePath + tag;
    const std::string ext = p.extension().string();
    return framePath.substr(0, framePath.size() - ext.size()) + tag + ext;
}

ImageCheck checkImage(const fs::path& path, const ImageExpectation& expected) {
    const auto fail = [](std::string why) { return ImageCheck{false, std::move(why)}; };
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return fail("missing");
    ImageFile file;
    // One read: a file cut short keeps an intact header, so its pixel error is reported after the header checks.
    const std::string why = readImageFile(path.string(), ImageRead::HeaderAndPixels, file);
    if (file.format.empty()) return fail("unreadable: " + why);
    if (file.format != "openexr") return fail("not an OpenEXR file");
    if (file.full_x != 0 || file.full_y != 0 || file.full_width != expected.width ||
        file.full_height != expected.height)
        return fail("display window " + std::to_string(file.full_width) + "x" + std::to_string(file.full_height) +
                    " differs from " + std::to_string(expected.width) + "x" + std::to_string(expected.height));
    if (!file.flat || !(file.window == expected.window))
        return fail("data window " + toString(file.window) + " differs from " + toString(expected.window));
    if (!expected.channels.empty() && file.channels != expected.channels) {
        std::string names;
        for (const auto& n : file.channels) names += (names.empty() ? "" : ",") + n;
        return fail("channels " + names + " differ from the expected ones");
    }
    if (!expected.config_hash.empty()) {
        const std::string hash = file.stringAttribute(kConfigHashKey);
        if (hash != expected.config_hash)
            return fail("config hash \"" + hash + "\" differs from \"" + expected.config_hash + "\"");
    }
    // Reading every pixel is the only reliable test for a file cut short: the header of a truncated EXR
    // is intact, its missing chunks only show when read.
    if (!why.empty()) return fail("pixels unreadable: " + why);
    return {true, {}};
}

bool shardIsComplete(const fs::path& path, const ShardExpectation& shard) {
    return checkImage(path, {.width = shard.width,
                             .height = shard.height,
                             .window = shardWindow(shard.width, shard.height, shard.shard),
                             .config_hash = shard.config_hash,
                             .channels = shard.channels})
        .complete;
}

}  // namespace clipblur
