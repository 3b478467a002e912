#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>
#include "tests/support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

namespace {

// Runs a shell command line and returns the exit code of the process.
int run(const std::string& command) {
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string renderCommand(const fs::path& dir, const std::string& extra) {
    return std::string(CLIPBLUR_BINARY) + " render " + CLIPBLUR_SOURCE_DIR + "/configs/default.yaml" +
           " --set render.method=stochastic --set film.width=64 --set film.height=36 --set render.samples=4" +
           " --progress none " + extra + " > " + (dir / "stdout.txt").string() + " 2> " + (dir / "stderr.txt").string();
}

}  // namespace

TEST(RenderCommand, RendersFramesThroughAPattern) {
    const fs::path dir = testing::freshTempDir("clipblur_cli_render");
    const std::string out = (dir / "shot.####.exr").string();
    ASSERT_EQ(run(renderCommand(dir, "--frames 3-4 --threads 1 --out " + out)), 0);
    for (const char* name : {"shot.0003.exr", "shot.0004.exr", "shot.0003.stats.json", "shot.0004.stats.json"})
        EXPECT_TRUE(fs::exists(dir / name)) << name;
    auto in = OIIO::ImageInput::open((dir / "shot.0003.exr").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().full_width, 64);
    EXPECT_EQ(in->spec().get_string_attribute("clipblur:method"), "stochastic");
    EXPECT_EQ(in->spec().get_int_attribute("clipblur:samples"), 4);
}

TEST(RenderCommand, SeveralFramesWithoutAPatternIsAUsageError) {
    const fs::path dir = testing::freshTempDir("clipblur_cli_nopattern");
    EXPECT_EQ(run(renderCommand(dir, "--frames 0-2 --out " + (dir / "one.exr").string())), 2);
    EXPECT_FALSE(fs::exists(dir / "one.exr"));
}

// Warnings reach the user on stderr, not only the stats: the job's (a camera key inside a closed box, at
// its file and line) once, the render's (tiles past max_subframes) per frame.
TEST(RenderCommand, WarningsOfTheJobAndTheRenderGoToStderr) {
    const fs::path dir = testing::freshTempDir("clipblur_cli_warnings");
    const fs::path job = dir / "inside.yaml";
    std::ofstream(job) << "version: 1\n"
                          "film: {width: 32, height: 18}\n"
                          "camera:\n"
                          "  keys:\n"
                          "    - {time: 0, position: [0, 0, 0]}\n"
                          "objects:\n"
                          "  - name: room\n"
                          "    primitive: {type: box, size: [10, 10, 10]}\n";
    const std::string render = std::string(CLIPBLUR_BINARY) + " render " + job.string() + " --progress none --out " +
                               (dir / "inside.exr").string() + " > " + (dir / "stdout.txt").string() + " 2> " +
                               (dir / "stderr.txt").string();
    ASSERT_EQ(run(render), 0) << readFile(dir / "stderr.txt");
    const std::string job_warning = readFile(dir / "stderr.txt");
    EXPECT_NE(job_warning.find("clipblur: warning: " + job.string() + ":5:"), std::string::npos) << job_warning;
    EXPECT_NE(job_warning.find("is inside the bounds of closed"), std::string::npos) << job_warning;

    ASSERT_EQ(run(renderCommand(dir, "--set render.method=clipped --set render.time_integration=subframes"
                                     " --set render.max_subframes=2 --out " + (dir / "capped.exr").string())),
              0);
    const std::string render_warning = readFile(dir / "stderr.txt");
    EXPECT_NE(render_warning.find("clipblur: warning: frame 0: "), std::string::npos) << render_warning;
    EXPECT_NE(render_warning.find("needed more than max_subframes (2)"), std::string::npos) << render_warning;
}

TEST(RenderCommand, InterruptStopsWithoutOutputAndExits130) {
    const fs::path dir = testing::freshTempDir("clipblur_cli_interrupt");
    const fs::path out = dir / "slow.exr";
    const fs::path log = dir / "progress.txt";
    // Big enough to still be rendering long after its first tile (640x360, 256 samples). The signal is
    // sent once a progress line shows the render (and so the handler) is running: a fixed sleep raced
    // with start-up on a loaded machine, where a background job of `sh -c` still ignores SIGINT.
    const std::string render = std::string(CLIPBLUR_BINARY) + " render " + CLIPBLUR_SOURCE_DIR +
                               "/configs/default.yaml --set render.method=stochastic --set render.samples=256" +
                               " --progress lines --out " + out.string() + " 2>" + log.string();
    const std::string script = render + " & pid=$!; i=0; while [ ! -s " + log.string() +
                               " ] && [ $i -lt 600 ]; do sleep 0.1; i=$((i+1)); done; kill -INT $pid; wait $pid; exit $?";
    EXPECT_EQ(run("sh -c '" + script + "'"), 130) << readFile(log);
    EXPECT_FALSE(fs::exists(out));
}

}  // namespace clipblur

namespace clipblur {

// `render --reference`: a float render compared with itself has no error, and a job rendered against
// another seed's render reports the stochastic difference; a missing reference fails before rendering.
TEST(RenderCommand, ReferenceErrorGoesToTheStats) {
    const fs::path dir = testing::freshTempDir("clipblur_cli_reference");
    const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
    const std::string common = " --set output.half=false --set render.method=stochastic --set film.width=32"
                               " --set film.height=18 --set render.samples=4 --progress none";
    const std::string job = std::string(CLIPBLUR_BINARY) + " render " + CLIPBLUR_SOURCE_DIR + "/configs/default.yaml";
    const std::string quiet = " > " + (dir / "out.txt").string() + " 2>&1";
    const auto output = [&dir] {
        std::ifstream in(dir / "out.txt");
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    ASSERT_EQ(std::system((job + common + " --out " + a + quiet).c_str()), 0) << output();
    ASSERT_EQ(std::system((job + common + " --out " + b + " --reference " + a + quiet).c_str()), 0) << output();
    std::ifstream same(dir / "b.stats.json");
    std::string text((std::istreambuf_iterator<char>(same)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"rmse\": 0.0"), std::string::npos) << text;

    const std::string c = (dir / "c.exr").string();
    ASSERT_EQ(std::system((job + common + " --set render.seed=9 --out " + c + " --reference " + a + quiet).c_str()), 0)
        << output();
    std::ifstream other(dir / "c.stats.json");
    text.assign((std::istreambuf_iterator<char>(other)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"rmse\""), std::string::npos);
    EXPECT_EQ(text.find("\"rmse\": 0.0"), std::string::npos) << "another seed's noise must show";

    const int status = std::system((job + common + " --out " + (dir / "d.exr").string() + " --reference " +
                                    (dir / "missing.exr").string() + quiet).c_str());
    EXPECT_EQ(WEXITSTATUS(status), 3);
    EXPECT_FALSE(fs::exists(dir / "d.exr"));
}

}  // namespace clipblur
