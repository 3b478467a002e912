#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace clipblur {

// One file a render will write: its path and what it is, for messages ("image of frame 3").
struct PlannedOutput {
    std::filesystem::path path;
    std::string what;
};

// Checks, before any rendering, that every planned output can be written without harm: no two name
// the same file, none names an input (the job file, an OBJ file, a reference image), none is an
// existing folder, and each one's folder exists and is writable or can be created (no regular file on
// the way). Paths are compared after resolving '.', '..' and symbolic links of the folders that exist.
// Throws Error(ExitCode::Output) naming the file and both uses of it.
void checkPlannedOutputs(const std::vector<PlannedOutput>& outputs, const std::vector<std::filesystem::path>& inputs);

}  // namespace clipblur
