#include "io/exr_merge.h"

#include <cstddef>
#include <cstring>
#include <memory>

#include <OpenImageIO/imageio.h>

#include "io/atomic_file.h"
#include "io/shard.h"
#include "scene/error.h"

namespace clipblur {

namespace fs = std::filesystem;

// Fills the unknown fields of `expected` from the first shard whose header reads.
static FrameExpectation resolveExpectation(const std::string& framePath, int count, FrameExpectation expected) {
    const bool needSize = expected.width <= 0 || expected.height <= 0;
    if (!needSize && !expected.config_hash.empty() && !expected.channels.empty()) return expected;
    for (int i = 0; i < count; ++i) {
        auto in = OIIO::ImageInput::open(shardPath(framePath, {i, count}));
        if (!in) {
            OIIO::geterror();  // clear the pending global error so it cannot leak into a later message
            continue;
        }
        const OIIO::ImageSpec& spec = in->spec();
        if (needSize) {
            expected.width = spec.full_width;
            expected.height = spec.full_height;
        }
        if (expected.config_hash.empty()) expected.config_hash = spec.get_string_attribute(kConfigHashKey);
        if (expected.channels.empty()) expected.channels = spec.channelnames;
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
        auto in = OIIO::ImageInput::open(framePath);
        if (!in) {
            OIIO::geterror();
            return false;
        }
        want.width = in->spec().full_width;
        want.height = in->spec().full_height;
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

static bool samePixelTypes(const OIIO::ImageSpec& a, const OIIO::ImageSpec& b) {
    if (a.nchannels != b.nchannels) return false;
    for (int c = 0; c < a.nchannels; ++c)
        if (a.channelformat(c) != b.channelformat(c)) return false;
    return true;
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

    OIIO::ImageSpec outSpec;
    std::vector<std::byte> frame;
    std::size_t pixelBytes = 0;
    for (int i = 0; i < count; ++i) {
        const std::string path = shardPath(framePath, {i, count});
        auto in = OIIO::ImageInput::open(path);
        if (!in) throw Error(ExitCode::Output, "cannot reopen shard " + path + ": " + OIIO::geterror());
        const OIIO::ImageSpec& spec = in->spec();
        if (i == 0) {
            outSpec = spec;
            outSpec.x = 0;
            outSpec.y = 0;
            outSpec.width = width;
            outSpec.height = height;
            outSpec.erase_attribute(kTileIndexKey);
            outSpec.erase_attribute(kTileCountKey);
            pixelBytes = spec.pixel_bytes(true);
            frame.resize(pixelBytes * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
        } else if (!samePixelTypes(spec, outSpec)) {
            throw Error(ExitCode::Output, "shard " + path + " stores different pixel types than shard 0");
        }
        std::vector<std::byte> pixels(spec.image_bytes(true));
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeUnknown, pixels.data()))
            throw Error(ExitCode::Output, "cannot read shard " + path + ": " + in->geterror());
        const std::size_t rowBytes = pixelBytes * static_cast<std::size_t>(spec.width);
        for (int row = 0; row < spec.height; ++row) {
            const std::size_t dst = (static_cast<std::size_t>(spec.y + row) * width + spec.x) * pixelBytes;
            std::memcpy(frame.data() + dst, pixels.data() + row * rowBytes, rowBytes);
        }
    }

    writeAtomically(framePath, [&](const fs::path& temporary) {
        auto out = OIIO::ImageOutput::create(temporary.string());
        if (!out) throw Error(ExitCode::Output, "cannot create EXR writer: " + OIIO::geterror());
        if (!out->open(temporary.string(), outSpec))
            throw Error(ExitCode::Output, "cannot open " + temporary.string() + ": " + out->geterror());
        if (!out->write_image(OIIO::TypeUnknown, frame.data()))
            throw Error(ExitCode::Output, "cannot write " + framePath + ": " + out->geterror());
        if (!out->close()) throw Error(ExitCode::Output, "cannot finish " + framePath + ": " + out->geterror());
    });
}

}  // namespace clipblur
