#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scene/pixel_bounds.h"

namespace clipblur {

// Shard `index` of `count` equal-ish parts of one frame, as given to `render --tile I/N`.
// Shards per frame (--tile, --tiles): far more than any farm splits a frame into, and small enough that
// a shard's bookkeeping never matters beside its render.
inline constexpr int kMaxShards = 65536;
// Worker threads a command accepts (--threads, --cpus-per-task).
inline constexpr int kMaxThreads = 4096;

struct TileShard {
    int index = 0;
    int count = 1;
    friend bool operator==(const TileShard&, const TileShard&) = default;
};

// Metadata keys a shard EXR carries; the merged frame keeps every other key of shard 0.
inline constexpr std::string_view kConfigHashKey = "clipblur:configHash";
inline constexpr std::string_view kTileIndexKey = "clipblur:tileIndex";
inline constexpr std::string_view kTileCountKey = "clipblur:tileCount";

// Parses "I/N" with 0 <= I < N; throws Error(ExitCode::Usage) naming the bad text otherwise.
TileShard parseTileShard(std::string_view text);

// The grid a frame is cut into for `count` shards: cols * rows == count exactly, chosen so that
// blocks are as close to square as possible (squarer blocks share fewer edges with their
// neighbours and so waste less of the visibility work that straddles a shard border).
struct ShardGrid {
    int cols = 1;
    int rows = 1;
};
ShardGrid shardGrid(int width, int height, int count);

// The data window of shard `shard` of a width x height frame. Shards are numbered row-major over the
// grid; column c spans [floor(c*W/cols), floor((c+1)*W/cols)), rows likewise, so the shards never
// overlap, cover the frame exactly and differ in size by at most one pixel per axis. Throws
// Error(ExitCode::Usage) when the frame has fewer pixels than shards along every grid choice.
PixelBounds shardWindow(int width, int height, TileShard shard);

// "out.0001.exr" -> "out.0001.tile-3-of-8.exr": the shard tag goes before the extension so image tools
// still recognise the format.
std::string shardPath(const std::string& framePath, TileShard shard);

// What a finished image must look like to be accepted as complete.
struct ImageExpectation {
    int width = 0;                       // display window, origin (0, 0)
    int height = 0;
    PixelBounds window;                   // expected data window
    std::string config_hash;             // empty: not checked
    std::vector<std::string> channels;   // empty: not checked
};

struct ImageCheck {
    bool complete = false;
    std::string reason;  // why not, for messages; empty when complete
};

// Opens `path` as an EXR and checks display and data window, channels, the config hash metadata and
// that every pixel reads back; a truncated or half-written file is reported incomplete, never thrown.
ImageCheck checkImage(const std::filesystem::path& path, const ImageExpectation& expected);

// Shard `shard` of a width x height frame, as checkImage expects it (hash and channels empty: not checked).
struct ShardExpectation {
    int width = 0;
    int height = 0;
    TileShard shard{};
    std::string config_hash{};
    std::vector<std::string> channels{};
};
bool shardIsComplete(const std::filesystem::path& path, const ShardExpectation& expected);

}  // namespace clipblur
