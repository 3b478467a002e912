#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace clipblur::testing {

// Runs a shell command line; the process's exit code, or -1 when it did not exit normally.
int runShell(const std::string& command);
// Runs a shell command line and returns what it wrote to stdout.
std::string captureShell(const std::string& command);

// A new empty folder under the temporary folder (TMPDIR), named `name` and a unique suffix: ctest runs
// test processes side by side, so no two may share one.
std::filesystem::path freshTempDir(const std::string& name);

// A whole EXR read as float, channels interleaved as in the file.
struct ExrPixels {
    OIIO::ImageSpec spec;
    std::vector<float> pixels;

    float at(int channel, std::size_t pixel) const {
        return pixels[pixel * static_cast<std::size_t>(spec.nchannels) + static_cast<std::size_t>(channel)];
    }
    // Channel `name` at data-window pixel (x, y); fails the test and returns 0 when there is no such channel.
    float at(const std::string& name, int x, int y) const;
};
ExrPixels readExrPixels(const std::filesystem::path& path);

}  // namespace clipblur::testing
