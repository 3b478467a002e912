#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace clipblur::cli {

// Each subcommand registers its options and returns the action that runs it; the action returns the
// process exit code. Errors are thrown as clipblur::Error and reported once, in main.
using Action = std::function<int()>;

Action addMergeCommand(CLI::App& app);
Action addSubmitCommand(CLI::App& app);

}  // namespace clipblur::cli
