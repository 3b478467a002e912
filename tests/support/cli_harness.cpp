#include "support/cli_harness.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include <gtest/gtest.h>

namespace clipblur::testing {

int runShell(const std::string& command) {
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string captureShell(const std::string& command) {
    std::string text;
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
    if (!pipe) return text;
    char buffer[4096];
    while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe.get())) text.append(buffer, n);
    return text;
}

std::filesystem::path freshTempDir(const std::string& name) {
    // mkdtemp: unique even where processes of another PID namespace (another CI job) share the folder.
    std::string pattern = (std::filesystem::temp_directory_path() / (name + "_XXXXXX")).string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp " + pattern + " failed");
    return pattern;
}

float ExrPixels::at(const std::string& name, int x, int y) const {
    const int c = spec.channelindex(name);
    EXPECT_GE(c, 0) << name;
    return c < 0 ? 0.0f : at(c, static_cast<std::size_t>(y) * static_cast<std::size_t>(spec.width) + static_cast<std::size_t>(x));
}

ExrPixels readExrPixels(const std::filesystem::path& path) {
    ExrPixels e;
    auto in = OIIO::ImageInput::open(path.string());
    EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
    if (!in) return e;
    e.spec = in->spec();
    e.pixels.resize(static_cast<std::size_t>(e.spec.width) * static_cast<std::size_t>(e.spec.height) *
                    static_cast<std::size_t>(e.spec.nchannels));
    EXPECT_TRUE(in->read_image(0, 0, 0, e.spec.nchannels, OIIO::TypeDesc::FLOAT, e.pixels.data()));
    return e;
}

}  // namespace clipblur::testing
