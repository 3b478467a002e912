#include "io/slurm_script.h"

#include <algorithm>

#include "scene/error.h"

namespace clipblur {

FarmElement elementOf(const FarmPlan& plan, int id) {
    if (id < 0 || id >= plan.elementCount())
        throw Error(ExitCode::Usage, "array element " + std::to_string(id) + " outside 0.." +
                                         std::to_string(plan.elementCount() - 1));
    return {plan.first_frame + id / plan.tiles, id % plan.tiles};
}

int elementId(const FarmPlan& plan, int frame, int tile) {
    if (frame < plan.first_frame || frame > plan.last_frame || tile < 0 || tile >= plan.tiles)
        throw Error(ExitCode::Usage, "frame " + std::to_string(frame) + " tile " + std::to_string(tile) +
                                         " is not part of the submission");
    return (frame - plan.first_frame) * plan.tiles + tile;
}

std::string arraySpec(std::vector<int> ids) {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::string spec;
    for (std::size_t i = 0; i < ids.size();) {
        std::size_t j = i;
        while (j + 1 < ids.size() && ids[j + 1] == ids[j] + 1) ++j;
        if (!spec.empty()) spec += ',';
        spec += std::to_string(ids[i]);
        if (j > i) spec += '-' + std::to_string(ids[j]);
        i = j + 1;
    }
    return spec;
}

std::string shellQuote(std::string_view word) {
    std::string quoted = "'";
    for (char c : word) {
        if (c == '\'')
            quoted += "'\\''";
        else
            quoted += c;
    }
    return quoted + "'";
}

// #SBATCH lines are parsed by sbatch, not by a shell: a path with a space cannot be quoted there, so
// refuse rather than write a script that logs somewhere unexpected.
static std::string directivePath(const std::filesystem::path& p) {
    const std::string s = p.string();
    if (s.find_first_of(" \t\n\"'") != std::string::npos)
        throw Error(ExitCode::Usage, "Slurm directives cannot hold the path \"" + s +
                                         "\" (whitespace or quotes); choose an output folder without them");
    return s;
}

static std::string header(const FarmPlan& plan, const std::string& name, const std::string& log) {
    std::string h = "#!/bin/bash\n";
    h += "#SBATCH --job-name=" + plan.job_name + "-" + name + "\n";
    h += "#SBATCH --output=" + directivePath(plan.farm_dir / log) + "\n";
    h += "#SBATCH --chdir=" + directivePath(plan.workdir) + "\n";
    if (!plan.partition.empty()) h += "#SBATCH --partition=" + plan.partition + "\n";
    if (plan.cpus_per_task > 0) h += "#SBATCH --cpus-per-task=" + std::to_string(plan.cpus_per_task) + "\n";
    return h;
}

// "clipblur" "job" --set 'k=v' ...: the part every command in both scripts starts with.
static std::string jobWords(const FarmPlan& plan) {
    std::string words = shellQuote(plan.job_file.string());
    for (const auto& o : plan.overrides) words += " --set " + shellQuote(o);
    return words;
}

std::string renderArrayScript(const FarmPlan& plan, const std::vector<int>& ids) {
    if (ids.empty()) throw Error(ExitCode::Usage, "no array elements to submit");
    for (int id : ids) elementOf(plan, id);  // validates the range
    std::string s = header(plan, "render", "render-%A_%a.log");
    s += "#SBATCH --array=" + arraySpec(ids) + "\n";
    s += "set -euo pipefail\n";
    s += "clipblur=" + shellQuote(plan.clipblur.string()) + "\n";
    s += "id=${SLURM_ARRAY_TASK_ID:?run this script with sbatch --array}\n";
    s += "tiles=" + std::to_string(plan.tiles) + "\n";
    s += "frame=$((" + std::to_string(plan.first_frame) + " + id / tiles))\n";
    s += "tile=$((id % tiles))\n";
    // A requeued or duplicated element must not redo a finished shard.
    s += "if \"$clipblur\" merge " + jobWords(plan) +
         " --frames \"$frame-$frame\" --tiles \"$tiles\" --check --shard \"$tile\" >/dev/null 2>&1; then\n";
    s += "  echo \"clipblur: frame $frame tile $tile/$tiles already complete\"\n";
    s += "  exit 0\n";
    s += "fi\n";
    s += "exec \"$clipblur\" render " + jobWords(plan) + " --frames \"$frame-$frame\" --tile \"$tile/$tiles\"";
    if (plan.cpus_per_task > 0) s += " --threads " + std::to_string(plan.cpus_per_task);
    s += "\n";
    return s;
}

std::string mergeScript(const FarmPlan& plan) {
    std::string s = header(plan, "merge", "merge-%j.log");
    s += "set -euo pipefail\n";
    s += "exec " + shellQuote(plan.clipblur.string()) + " merge " + jobWords(plan) + " --frames " +
         std::to_string(plan.first_frame) + "-" + std::to_string(plan.last_frame) + " --tiles " +
         std::to_string(plan.tiles) + "\n";
    return s;
}

std::vector<std::string> sbatchCommand(const std::filesystem::path& script, const std::string& afterOk, bool wait) {
    std::vector<std::string> argv{"sbatch", "--parsable"};
    if (!afterOk.empty()) argv.push_back("--dependency=afterok:" + afterOk);
    if (wait) argv.push_back("--wait");
    argv.push_back(script.string());
    return argv;
}

std::string parseSbatchJobId(std::string_view output) {
    std::string_view s = output;
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.remove_suffix(1);
    // Warnings may precede the id; --parsable puts it on the last line.
    const std::size_t nl = s.rfind('\n');
    if (nl != std::string_view::npos) s.remove_prefix(nl + 1);
    const std::size_t semi = s.find(';');
    if (semi != std::string_view::npos) s = s.substr(0, semi);
    if (s.empty() || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }))
        throw Error(ExitCode::Output, "sbatch printed no job id: \"" + std::string(output) + "\"");
    return std::string(s);
}

}  // namespace clipblur
