#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/cli_test_util.h"
#include "tests/io/config/config_test_util.h"

extern char** environ;

namespace clipblur {

namespace fs = std::filesystem;
using testing::runShell;
using testing::testDir;
using testing::readText;
using testing::smallRender;
using testing::temporariesIn;

// Issue 24, kind 5: an output that fails after the EXR was written had already replaced it. Every
// failure leaves the earlier image and stats byte for byte, and no temporary behind.
TEST(RenderOutputs, AFailingOutputLeavesEveryEarlierOutputAsItWas) {
    const fs::path dir = testDir();
    const std::string out = " --out " + (dir / "img.exr").string(), no_png = " --set output.png_preview=false";
    ASSERT_EQ(runShell(smallRender(dir, out + no_png)), 0) << readText(dir / "err.txt");
    const std::string image = readText(dir / "img.exr"), stats = readText(dir / "img.stats.json");
    fs::create_directories(dir / "img.png");
    std::ofstream(dir / "file") << "x";
    // Another seed, so a rewritten image would differ in its pixels too.
    for (const std::string& extra : std::vector<std::string>{" --set output.png_preview=true", no_png + " --stats " + (dir / "file" / "s.json").string(),
                                    no_png + " --set output.stats=" + (dir / "img.png").string()}) {
        SCOPED_TRACE(extra);
        EXPECT_EQ(runShell(smallRender(dir, out + " --set render.seed=7" + extra)), 5) << readText(dir / "err.txt");
        EXPECT_EQ(readText(dir / "img.exr"), image);
        EXPECT_EQ(readText(dir / "img.stats.json"), stats);
        EXPECT_EQ(temporariesIn(dir), 0);
    }
}

// Issue 24, kind 4: --stats naming the image wrote the stats over it. Collisions between any two
// outputs of any frames are refused before rendering, naming both.
TEST(RenderOutputs, CollidingOutputsAreRefusedBeforeRendering) {
    const fs::path dir = testDir();
    const std::string d = dir.string();
    const std::vector<std::pair<std::string, std::string>> cases{
        {" --out " + d + "/a.exr --stats " + d + "/a.exr", "stats of frame 0 would overwrite the image of frame 0"},
        {" --out " + d + "/a.exr --stats " + d + "/sub/../a.exr", "would overwrite the image"},
        {" --out " + d + "/a.exr --stats " + d + "/link/a.exr", "would overwrite the image"},
        {" --out " + d + "/f#.exr --stats " + d + "/f1#.exr --frames 0-10", "image of frame 10 would overwrite the stats of frame 0"},
        {" --out " + d + "/a.png --set output.png_preview=true", "PNG preview of frame 0 would overwrite the image"},
        {" --out " + d + "/a.exr --set output.stats=" + d + "/a.png --set output.png_preview=true", "would overwrite the PNG preview"},
    };
    fs::create_directories(dir / "sub");
    fs::create_directory_symlink(dir, dir / "link");
    for (const auto& [extra, says] : cases) {
        SCOPED_TRACE(extra);
        EXPECT_EQ(runShell(smallRender(dir, extra)), 5);
        EXPECT_NE(readText(dir / "err.txt").find(says), std::string::npos) << readText(dir / "err.txt");
        EXPECT_EQ(readText(dir / "out.txt"), "") << "nothing rendered";
    }
    EXPECT_FALSE(fs::exists(dir / "a.exr"));
    EXPECT_FALSE(fs::exists(dir / "f10.exr"));
}

// --resume skips a frame whose image is complete for this job; a missing, cut-short or other job's
// image is rendered again.
TEST(RenderOutputs, ResumeRendersOnlyWhatIsMissing) {
    const fs::path dir = testDir();
    const std::string render = " --frames 0-3 --out " + (dir / "f.#.exr").string();
    ASSERT_EQ(runShell(smallRender(dir, render + " --resume")), 0);
    fs::remove(dir / "f.1.exr");
    const std::string whole = readText(dir / "f.2.exr");
    std::ofstream(dir / "f.2.exr", std::ios::binary) << whole.substr(0, whole.size() / 2);
    ASSERT_EQ(runShell(smallRender(dir, render + " --resume")), 0);
    const std::string log = readText(dir / "out.txt");
    EXPECT_NE(log.find("frame 0: " + (dir / "f.0.exr").string() + " complete, skipped"), std::string::npos) << log;
    EXPECT_NE(log.find("frame 1: wrote"), std::string::npos) << log;
    EXPECT_NE(log.find("frame 2: wrote"), std::string::npos) << log;
    EXPECT_NE(log.find("frame 3: " + (dir / "f.3.exr").string() + " complete, skipped"), std::string::npos) << log;

    ASSERT_EQ(runShell(smallRender(dir, render + " --resume --set render.seed=3")), 0);
    EXPECT_EQ(readText(dir / "out.txt").find("skipped"), std::string::npos) << "another job's frames are not done";
    ASSERT_EQ(runShell(smallRender(dir, render)), 0);
    EXPECT_EQ(readText(dir / "out.txt").find("skipped"), std::string::npos) << "without --resume every frame renders";
}

namespace {

// Whether process `pid` has a handler for `sig` (the SigCgt mask of /proc/PID/status).
bool catches(pid_t pid, int sig) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (sig - 1)) & 1u;
    return false;
}

// A job slow to load: 24 objects of one 160x160-quad grid OBJ (1.2 million triangles, few bytes).
fs::path slowJob(const fs::path& dir) {
    std::ofstream obj(dir / "grid.obj");
    const int n = 160;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) obj << "v " << i << " " << j << " 0\n";
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i + 1;
            obj << "f " << a << " " << a + 1 << " " << a + n + 2 << " " << a + n + 1 << "\n";
        }
    std::ofstream job(dir / "job.yaml");
    job << "version: 1\ncamera: {keys: [{position: [80, 80, -100]}]}\nfilm: {width: 8, height: 8}\nobjects:\n";
    for (int k = 0; k < 24; ++k) job << "  - {obj: grid.obj}\n";
    return dir / "job.yaml";
}

}  // namespace

// Issue 24, kind 7: a signal while the job loaded ended the process without exit 130 and message.
// The signal is sent as soon as the process catches it, long before a job this size has loaded.
TEST(RenderOutputs, StopSignalWhileLoadingExits130) {
    const fs::path dir = testDir();
    const std::string job = slowJob(dir).string(), out = (dir / "o.exr").string(), err = (dir / "err.txt").string();
    for (const int sig : {SIGINT, SIGTERM}) {
        SCOPED_TRACE(sig);
        std::vector<std::string> args{CLIPBLUR_BINARY, "render", job, "--out", out, "--progress", "none"};
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t files;
        posix_spawn_file_actions_init(&files);
        posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        pid_t pid = 0;
        ASSERT_EQ(posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), environ), 0);
        posix_spawn_file_actions_destroy(&files);
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (!catches(pid, sig) && std::chrono::steady_clock::now() < give_up)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        kill(pid, sig);
        int status = 0;
        waitpid(pid, &status, 0);
        ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal";
        EXPECT_EQ(WEXITSTATUS(status), 130);
        EXPECT_NE(readText(err).find("interrupted while loading the job"), std::string::npos) << readText(err);
        EXPECT_FALSE(fs::exists(out));
    }
}

}  // namespace clipblur
