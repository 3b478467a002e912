#include "io/exr_merge.h"

#include <cstddef>
#include <cstring>
#include <memory>

#include "io/atomic_file.h"
#include "io/shard.h"
#include "io/image_files.h"
#include "scene/error.h"

namespace clipblur {

namespace fs = std::filesystem;

// Fills the unknown fields of `expected` from the first shard whose header reads.
static FrameExpectation resolveExpectation(const std::string& framePath, int count, FrameExpectation expected) {
    const bool needSize = expected.width <= 0 || expected.height <= 0;
    if (!needSize && !expected.config_hash.empty() && !expected.channels.empty()) return expected;
    for (int i = 0; i < count; ++i) {
        ImageFile file;
        if (!readImageFile(shardPath(framePath, {i, count}), ImageRead::Header, file).empty()) continue;
        if (needSize) {
            expected.width = file.full_width;
            expected.height = file.full_height;
        }
        if (expected.config_hash.empty()) expected.config_hash = file.stringAttribute(kConfigHashKey);
        if (expected.channels.empty()) expected.channels = file.channels;
        break;
    }
    return expected;
}

ShardSetCheck checkShards(const std::string& framePath, int count, const FrameExpectation& expected) {
    if (count < 1) throw Error(ExitCode::Usage, "tile count must be at least 1");
    ShardSetCheck result;
    result.resolved = resolveExpectation(framePath, count, expected);
    for (int i = 0; i < count; ++i) {
        const TileShard shard{i, count};
        const std::string path = shardPath(framePath, shard);
        ImageCheck check;
        if (result.resolved.width <= 0 || result.resolved.height <= 0) {
            check.reason = "missing";
        } else {
            ImageExpectation want;
            want.width = result.resolved.width;
            want.height = result.resolved.height;
            want.window = shardWindow(want.width, want.height, shard);
            want.config_hash = result.resolved.config_hash;
            want.channels = result.resolved.channels;
            check = checkImage(path, want);
        }
        if (!check.complete) {
            result.incomplete.push_back(i);
            result.reasons.push_back(path + ": " + check.reason);
        }
    }
    return result;
}

bool frameIsMerged(const std::string& framePath, const FrameExpectation& expected) {
    ImageExpectation want;
    want.width = expected.width;
    want.height = expected.height;
    if (want.width <= 0 || want.height <= 0) {
        ImageFile file;
        if (!readImageFile(framePath, ImageRead::Header, file).empty()) return false;
        want.width = file.full_width;
        want.height = file.full_height;
    }
    want.window = PixelBounds::sized(0, 0, want.width, want.height);
    want.config_hash = expected.config_hash;
    want.channels = expected.channels;
    return checkImage(framePath, want).complete;
}

std::vector<int> pendingShards(const std::string& framePath, int count, const FrameExpectation& expected) {
    if (frameIsMerged(framePath, expected)) return {};
    return checkShards(framePath, count, expected).incomplete;
}

void mergeShards(const std::string& framePath, int count, const FrameExpectation& expected) {
    const ShardSetCheck check = checkShards(framePath, count, expected);
    if (!check.complete()) {
        std::string message = "cannot merge " + framePath + ": " + std::to_string(check.incomplete.size()) + " of " +
                              std::to_string(count) + " shards incomplete";
        for (const auto& reason : check.reasons) message += "\n  " + reason;
        throw Error(ExitCode::Output, message);
    }
    const int width = check.resolved.width;
    const int height = check.resolved.height;

    ImageFile frame;
    for (int i = 0; i < count; ++i) {
        const std::string path = shardPath(framePath, {i, count});
        ImageFile shard;
        if (const std::string why = readImageFile(path, ImageRead::HeaderAndPixels, shard); !why.empty())
            throw Error(ExitCode::Output, "cannot read shard " + path + ": " + why);
        if (i == 0) {
            frame = shard;
            frame.window = PixelBounds::sized(0, 0, width, height);
            frame.erase(kTileIndexKey);
            frame.erase(kTileCountKey);
            frame.pixels.assign(frame.window.area() * frame.channels.size(), 0.0f);
        } else if (shard.types != frame.types) {
            throw Error(ExitCode::Output, "shard " + path + " stores different pixel types than shard 0");
        }
        // Half and float values pass through float unchanged, so the merged file holds the shards' bits.
        const std::size_t nc = frame.channels.size();
        const std::size_t row = nc * static_cast<std::size_t>(shard.window.width());
        for (int y = 0; y < shard.window.height(); ++y)
            std::memcpy(frame.pixels.data() + frame.window.index(shard.window.x0, shard.window.y0 + y) * nc,
                        shard.pixels.data() + static_cast<std::size_t>(y) * row, row * sizeof(float));
    }

    writeAtomically(framePath, [&](const fs::path& temporary) {
        if (const std::string why = writeImageFile(temporary.string(), frame); !why.empty())
            throw Error(ExitCode::Output, "cannot write " + framePath + ": " + why);
    });
}

}  // namespace clipblur
