#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace clipblur::cli {

// Each subcommand registers its options and returns the action that runs it; the action returns the
// process exit code. Errors are thrown as clipblur::Error and reported once, in main.
using Action = std::function<int()>;

// `clipblur validate JOB [--set key=value]...`: loads and checks a job, prints a summary.
Action addValidateCommand(CLI::App& app);

// clipblur paths: image-plane vertex paths of the paper's Table 1 (section 2.4).
Action addPathsCommand(CLI::App& app);

// `clipblur render JOB [--set k=v]... [--threads N] [--frames A-B] [--out PATH] [--stats PATH]
// [--progress auto|bar|lines|none] [--tile I/N] [--reference REF] [--resume]`: renders every frame to
// OpenEXR (plus stats JSON and an optional PNG preview), a frame's files moved into place together. Every
// output path is checked before rendering (exit 5). With --tile only shard I of N is rendered, into the
// frame's shard path with its data window, and a shard already complete is skipped; --resume skips
// complete whole frames alike. SIGINT/SIGTERM, while loading or rendering, stop without writing the
// frame; exit code 130.
Action addRenderCommand(CLI::App& app);

// `clipblur scene-json JOB [--set key=value]...`: prints the loaded, expanded scene as JSON
// (cli/scene_json_command.h), for external peers that rebuild the scene (scripts/bench/cycles_peer.py).
Action addSceneJsonCommand(CLI::App& app);

Action addMergeCommand(CLI::App& app);
Action addSubmitCommand(CLI::App& app);

}  // namespace clipblur::cli
