#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "cli/commands.h"
#include "io/exr_merge.h"
#include "io/frame_path.h"
#include "io/job_loader.h"
#include "io/shard.h"
#include "io/slurm_script.h"
#include "scene/error.h"

namespace clipblur::cli {

namespace fs = std::filesystem;

namespace {

struct SubmitOptions {
    std::string job;
    std::vector<std::string> overrides;
    std::string engine;
    std::string frames;
    int tiles = 1;
    std::string partition;
    int cpus_per_task = 0;
    std::string binary;
    bool dry_run = false;
    bool wait = false;
};

// Runs argv through the shell with every word quoted, returns its stdout; stderr passes through so
// sbatch's own messages reach the user.
std::string run(const std::vector<std::string>& argv) {
    std::string command;
    for (const auto& word : argv) command += (command.empty() ? "" : " ") + shellQuote(word);
    std::FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) throw Error(ExitCode::Output, "cannot run " + argv.front());
    std::string output;
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    const int status = ::pclose(pipe);
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        const int code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
        throw Error(ExitCode::Output, command + " failed (exit " + std::to_string(code) + ")" +
                                          (code == 127 ? ": is Slurm's sbatch installed and on PATH?" : ""));
    }
    return output;
}

void writeScript(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::trunc);
    out << text;
    if (!out.flush()) throw Error(ExitCode::Output, "cannot write " + path.string());
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
}

int submit(const SubmitOptions& o) {
    if (o.engine != "slurm") throw Error(ExitCode::Usage, "unknown engine \"" + o.engine + "\" (only slurm)");
    const RenderJob job = loadJob(o.job, o.overrides);

    FarmPlan plan;
    plan.clipblur = o.binary.empty() ? fs::read_symlink("/proc/self/exe") : fs::absolute(o.binary).lexically_normal();
    plan.job_file = fs::absolute(o.job).lexically_normal();
    plan.overrides = o.overrides;
    plan.workdir = fs::current_path();
    plan.first_frame = job.frames.first;
    plan.last_frame = job.frames.last;
    if (!o.frames.empty()) {
        const FrameRange r = parseFrameRange(o.frames);
        plan.first_frame = r.first;
        plan.last_frame = r.last;
    }
    plan.tiles = o.tiles;
    plan.partition = o.partition;
    plan.cpus_per_task = o.cpus_per_task;
    const fs::path firstFrame = fs::absolute(outputPathForFrame(job.output.path, plan.first_frame, plan.first_frame, plan.last_frame));
    plan.farm_dir = (firstFrame.parent_path() / ".clipblur-farm").lexically_normal();

    FrameExpectation expected;
    expected.width = job.scene.film.width;
    expected.height = job.scene.film.height;
    expected.config_hash = job.config_hash;
    std::vector<int> pending;
    for (int f = plan.first_frame; f <= plan.last_frame; ++f)
        for (int tile : pendingShards(outputPathForFrame(job.output.path, f, plan.first_frame, plan.last_frame), plan.tiles, expected))
            pending.push_back(elementId(plan, f, tile));

    const std::string merge = mergeScript(plan);
    const std::string render = pending.empty() ? std::string() : renderArrayScript(plan, pending);
    std::cout << pending.size() << " of " << plan.elementCount() << " shards to render"
              << (pending.empty() ? "" : " (array " + arraySpec(pending) + ")") << "\n";
    if (o.dry_run) {
        if (!render.empty()) std::cout << "---- " << (plan.farm_dir / "render.sh").string() << "\n" << render;
        std::cout << "---- " << (plan.farm_dir / "merge.sh").string() << "\n" << merge;
        return 0;
    }

    std::error_code ec;
    fs::create_directories(plan.farm_dir, ec);
    if (ec) throw Error(ExitCode::Output, "cannot create " + plan.farm_dir.string() + ": " + ec.message());
    std::string renderId;
    if (!render.empty()) {
        writeScript(plan.farm_dir / "render.sh", render);
        renderId = parseSbatchJobId(run(sbatchCommand(plan.farm_dir / "render.sh")));
        std::cout << "render job " << renderId << "\n" << std::flush;
    }
    writeScript(plan.farm_dir / "merge.sh", merge);
    if (o.wait) {
        // sbatch --wait prints the id at submission and returns when the job ends, with its exit code.
        std::cout << "merge job (waiting)\n" << std::flush;
        const std::string mergeId = parseSbatchJobId(run(sbatchCommand(plan.farm_dir / "merge.sh", renderId, true)));
        std::cout << "merge job " << mergeId << " ended\n";
        // Slurm cancels a merge whose render array failed and sbatch --wait still exits 0 for it, so the
        // frames on disk are the only trustworthy verdict.
        std::vector<std::string> unmerged;
        for (int f = plan.first_frame; f <= plan.last_frame; ++f) {
            const std::string path = outputPathForFrame(job.output.path, f, plan.first_frame, plan.last_frame);
            if (!frameIsMerged(path, expected)) unmerged.push_back(path);
        }
        if (!unmerged.empty()) {
            std::string message = std::to_string(unmerged.size()) + " frame(s) not merged; logs in " +
                                  plan.farm_dir.string() + "; the same submit renders only what is missing";
            for (const auto& path : unmerged) message += "\n  " + path;
            throw Error(ExitCode::Render, message);
        }
    } else {
        const std::string mergeId = parseSbatchJobId(run(sbatchCommand(plan.farm_dir / "merge.sh", renderId)));
        std::cout << "merge job " << mergeId << "\n";
    }
    return 0;
}

}  // namespace

Action addSubmitCommand(CLI::App& app) {
    auto options = std::make_shared<SubmitOptions>();
    CLI::App* sub = app.add_subcommand("submit", "Render a job on a farm: one array element per frame and tile");
    sub->add_option("job", options->job, "Render job file (YAML or JSON)")->required();
    sub->add_option("--set", options->overrides, "Override a job value, key.path=value (passed to every node)");
    sub->add_option("--engine", options->engine, "Scheduler: slurm")->required();
    sub->add_option("--frames", options->frames, "Frame range A-B (default: the job's)");
    sub->add_option("--tiles", options->tiles, "Shards per frame")->check(CLI::Range(1, kMaxShards));
    sub->add_option("--partition", options->partition, "Slurm partition (default: the cluster's)");
    sub->add_option("--cpus-per-task", options->cpus_per_task, "CPUs per element, also render --threads")
        ->check(CLI::Range(0, kMaxThreads));
    sub->add_option("--binary", options->binary, "clipblur as the nodes see it (default: this binary)");
    sub->add_flag("--dry-run", options->dry_run, "Print the scripts, submit nothing");
    sub->add_flag("--wait", options->wait, "Return when the merge job ends, with its success or failure");
    return [options]() { return submit(*options); };
}

}  // namespace clipblur::cli
