#pragma once

#include <string>
#include <vector>

namespace clipblur {

// What every shard of one frame must agree on. Fields left empty are taken from the first shard that
// opens, so a path-only merge still demands that all shards match each other.
struct FrameExpectation {
    int width = 0;   // display window; 0: from the shards
    int height = 0;
    std::string config_hash;            // empty: from the shards
    std::vector<std::string> channels;  // empty: from the shards
};

struct ShardSetCheck {
    FrameExpectation resolved;         // the expectation actually checked against
    std::vector<int> incomplete;       // shard indices, ascending
    std::vector<std::string> reasons;  // one per incomplete shard
    bool complete() const { return incomplete.empty(); }
};

// Checks shards 0..count-1 of `framePath` (named by shardPath) against `expected`.
ShardSetCheck checkShards(const std::string& framePath, int count, const FrameExpectation& expected = {});

// Assembles the `count` shards of `framePath` into the full frame at `framePath`, written atomically.
// Pixels are copied in the stored type (half stays half, bit for bit); the data window is the display
// window; metadata comes from shard 0 without the tile keys. Throws Error(ExitCode::Output) naming every
// incomplete shard, or shards that disagree on pixel types, and writes nothing then.
void mergeShards(const std::string& framePath, int count, const FrameExpectation& expected = {});

// Checks the merged frame itself: an EXR whose data window is its whole display window and that matches
// the known fields of `expected` (an unknown size is taken from the file).
bool frameIsMerged(const std::string& framePath, const FrameExpectation& expected = {});

// Shards of `framePath` that still have to be rendered: none when the merged frame is already complete,
// else every incomplete shard. A resubmission renders exactly these.
std::vector<int> pendingShards(const std::string& framePath, int count, const FrameExpectation& expected = {});

}  // namespace clipblur
