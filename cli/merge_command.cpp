#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "io/exr_merge.h"
#include "io/frame_path.h"
#include "io/job_loader.h"
#include "io/shard.h"
#include "scene/error.h"

namespace clipblur::cli {

namespace {

struct MergeOptions {
    std::string job;
    std::vector<std::string> overrides;
    std::string out;
    std::string frames;
    int tiles = 0;
    bool check = false;
    int shard = -1;
};

// Frame pattern, frame range and what the shards must match, from the job when one is given.
struct MergeTarget {
    std::string pattern;
    FrameRange frames;
    FrameExpectation expected;
};

MergeTarget resolveTarget(const MergeOptions& o) {
    MergeTarget t;
    if (!o.job.empty()) {
        const RenderJob job = loadJob(o.job, o.overrides);
        t.pattern = job.output.path;
        t.frames = job.frames;
        t.expected.width = job.scene.film.width;
        t.expected.height = job.scene.film.height;
        t.expected.config_hash = job.config_hash;
    } else {
        if (!o.overrides.empty()) throw Error(ExitCode::Usage, "--set needs a JOB");
        if (o.out.empty()) throw Error(ExitCode::Usage, "merge needs a JOB or --out PATTERN");
        if (o.frames.empty()) throw Error(ExitCode::Usage, "merge --out needs --frames A-B");
        t.pattern = o.out;
    }
    if (!o.out.empty()) t.pattern = o.out;
    if (!o.frames.empty()) {
        const FrameRange r = parseFrameRange(o.frames);
        t.frames.first = r.first;
        t.frames.last = r.last;
    }
    return t;
}

// Reports what is missing; true when every frame is merged or has all its shards.
bool check(const MergeOptions& o, const MergeTarget& t) {
    bool complete = true;
    for (int f = t.frames.first; f <= t.frames.last; ++f) {
        const std::string path = outputPathForFrame(t.pattern, f, t.frames.first, t.frames.last);
        if (frameIsMerged(path, t.expected)) continue;
        const ShardSetCheck shards = checkShards(path, o.tiles, t.expected);
        for (std::size_t k = 0; k < shards.incomplete.size(); ++k) {
            if (o.shard >= 0 && shards.incomplete[k] != o.shard) continue;
            complete = false;
            std::cout << "missing " << shards.reasons[k] << "\n";
        }
    }
    return complete;
}

int merge(const MergeOptions& o, const MergeTarget& t) {
    for (int f = t.frames.first; f <= t.frames.last; ++f) {
        const std::string path = outputPathForFrame(t.pattern, f, t.frames.first, t.frames.last);
        const ShardSetCheck shards = checkShards(path, o.tiles, t.expected);
        // Shards may be cleaned up after a merge; a complete merged frame then counts as done.
        if (!shards.complete() && frameIsMerged(path, t.expected)) {
            std::cout << "already merged " << path << "\n";
            continue;
        }
        mergeShards(path, o.tiles, t.expected);
        std::cout << "merged " << path << " from " << o.tiles << " shards\n";
    }
    return 0;
}

}  // namespace

Action addMergeCommand(CLI::App& app) {
    auto options = std::make_shared<MergeOptions>();
    CLI::App* sub = app.add_subcommand("merge", "Assemble tile shards (render --tile I/N) into full frames");
    sub->add_option("job", options->job, "Render job file (YAML or JSON); gives output path, frames, hash");
    sub->add_option("--set", options->overrides, "Override a job value, key.path=value (as given to render)");
    sub->add_option("--out", options->out, "Frame path pattern, '#' runs become the frame number");
    sub->add_option("--frames", options->frames, "Frame range A-B (default: the job's)");
    sub->add_option("--tiles", options->tiles, "Number of shards per frame")->required()->check(CLI::Range(1, kMaxShards));
    sub->add_flag("--check", options->check, "Only report missing shards; exit 0 when nothing is missing, 5 else");
    sub->add_option("--shard", options->shard, "With --check: look at this shard index only")
        ->check(CLI::Range(0, kMaxShards - 1));
    return [options]() {
        const MergeOptions& o = *options;
        if (o.shard >= 0 && !o.check) throw Error(ExitCode::Usage, "--shard only goes with --check");
        if (o.shard >= o.tiles) throw Error(ExitCode::Usage, "--shard must be below --tiles");
        const MergeTarget target = resolveTarget(o);
        if (o.check) return check(o, target) ? 0 : static_cast<int>(ExitCode::Output);
        return merge(o, target);
    };
}

}  // namespace clipblur::cli
