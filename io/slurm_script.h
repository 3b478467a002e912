#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace clipblur {

// Everything a farm submission needs to write its sbatch scripts. One Slurm array element renders one
// (frame, tile) shard; element id = (frame - first_frame) * tiles + tile.
struct FarmPlan {
    std::filesystem::path clipblur;       // absolute path of the binary the nodes run
    std::filesystem::path job_file;       // absolute
    std::vector<std::string> overrides;   // --set values, passed to render and merge unchanged
    std::filesystem::path workdir;        // cwd of every element, so relative job paths mean the same
    std::filesystem::path farm_dir;       // scripts and logs
    int first_frame = 0;
    int last_frame = 0;
    int tiles = 1;
    std::string partition;                // empty: the cluster's default partition
    int cpus_per_task = 0;                // 0: Slurm's default, and render picks its own thread count
    std::string job_name = "clipblur";

    int elementCount() const { return (last_frame - first_frame + 1) * tiles; }
};

struct FarmElement {
    int frame = 0;
    int tile = 0;
    friend bool operator==(const FarmElement&, const FarmElement&) = default;
};

FarmElement elementOf(const FarmPlan& plan, int id);
int elementId(const FarmPlan& plan, int frame, int tile);

// Slurm array syntax for a set of ids: sorted, duplicates dropped, runs collapsed ("0-3,5,7-8").
std::string arraySpec(std::vector<int> ids);

// Quotes one word for POSIX sh so that spaces, quotes and $ survive: 'it'\''s'.
std::string shellQuote(std::string_view word);

// The array script; its --array line lists `ids` only, so a resubmission renders just what is missing.
std::string renderArrayScript(const FarmPlan& plan, const std::vector<int>& ids);

// The merge script: `clipblur merge` over the whole frame range.
std::string mergeScript(const FarmPlan& plan);

// argv of the sbatch call for `script`; `afterOk` (a job id, may be empty) makes it wait for that job's
// success. --parsable makes sbatch print just the id.
std::vector<std::string> sbatchCommand(const std::filesystem::path& script, const std::string& afterOk = {},
                                       bool wait = false);

// The job id from `sbatch --parsable` output ("1234" or "1234;cluster"); throws Error(ExitCode::Output).
std::string parseSbatchJobId(std::string_view output);

}  // namespace clipblur
