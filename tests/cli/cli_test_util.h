#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/cli_harness.h"

namespace clipblur::testing {

inline std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// `clipblur render` of `job` (configs/default.yaml) at 16x9 with one stochastic sample (a frame takes
// milliseconds), then `extra`; stdout and stderr go to out.txt and err.txt in `dir`.
inline std::string smallRender(const std::filesystem::path& dir, const std::string& extra,
                               const std::string& job = std::string(CLIPBLUR_SOURCE_DIR) + "/configs/default.yaml") {
    return std::string(CLIPBLUR_BINARY) + " render " + job +
           " --set render.method=stochastic --set film.width=16 --set film.height=9 --set render.samples=1" +
           " --progress none " + extra + " > " + (dir / "out.txt").string() + " 2> " + (dir / "err.txt").string();
}

// Files under `dir` named ".tmp-*": temporaries an atomic write left behind.
inline int temporariesIn(const std::filesystem::path& dir) {
    int count = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
        count += e.path().filename().string().rfind(".tmp-", 0) == 0;
    return count;
}

}  // namespace clipblur::testing
