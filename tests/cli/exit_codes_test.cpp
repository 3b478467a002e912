#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/cli_test_util.h"
#include "tests/io/config/config_test_util.h"

namespace clipblur {

namespace fs = std::filesystem;
using testing::runShell;
using testing::testDir;
using testing::readText;
using testing::smallRender;

namespace {

struct ExitCase {
    std::string name;
    std::string extra;  // arguments after smallRender's
    int code;
    std::string says;  // in stderr
};

// A job in `dir` with one object from `obj`, which holds `text`.
fs::path objJob(const fs::path& dir, const std::string& text) {
    std::ofstream(dir / "mesh.obj") << text;
    std::ofstream(dir / "job.yaml") << "version: 1\ncamera: {keys: [{position: [0, 0, -3]}]}\nfilm: {width: 8, height: 8}\n"
                                       "objects:\n  - obj: mesh.obj\n";
    return dir / "job.yaml";
}

}  // namespace

// README's exit codes, one case of each kind of failure: the code, the message, and no image written.
TEST(ExitCodes, EachKindOfFailureHasItsDocumentedCode) {
    const fs::path dir = testDir();
    fs::create_directories(dir / "folder.png");
    std::ofstream(dir / "plain.txt") << "a file";
    const std::string out = " --out " + (dir / "img.exr").string();
    const std::vector<ExitCase> cases{
        {"ok", out, 0, ""},
        {"unknown flag", out + " --bogus", 2, "bogus"},
        {"frame past the limit", out + " --frames 2147483647", 2, "within -1000000..1000000"},
        {"too many frames", " --out " + (dir / "f.#.exr").string() + " --frames 0-1000000", 2, "more than 1000000 frames"},
        {"bad tile", out + " --tile 3/2", 2, "index out of range"},
        {"too many shards", out + " --tile 1/65537", 2, "count must be in 1..65536"},
        {"shard count overflows int", out + " --tile 1/99999999999", 2, "not an integer in 1..65536"},
        {"negative threads", out + " --threads -1", 2, "not in range 0 to 4096"},
        {"too many threads", out + " --threads 100000000", 2, "not in range 0 to 4096"},
        {"empty --set value", out + " --set film.width=", 3, "has no value after '='"},
        {"zero view", out + " --set 'camera.keys.0.view=[0, 0, 0]'", 3, "must not be the zero vector"},
        {"view parallel to up", out + " --set 'camera.keys.0.view=[0, 2, 0]'", 3, "parallel"},
        {"up parallel to view", out + " --set 'camera.keys.1.up=[0.3, -1.5, 8]'", 3, "parallel"},
        {"film too wide", out + " --set film.width=16385", 3, "16384"},
        {"missing reference", out + " --reference " + (dir / "none.exr").string(), 3, "reference image"},
        {"stats over the image", out + " --stats " + (dir / "img.exr").string(), 5, "would overwrite the image"},
        {"preview is a folder", " --out " + (dir / "folder.exr").string() + " --set output.png_preview=true", 5,
         "is a folder"},
        {"stats under a file", out + " --stats " + (dir / "plain.txt" / "s.json").string(), 5, "is not a folder"},
    };
    for (const ExitCase& c : cases) {
        SCOPED_TRACE(c.name);
        fs::remove(dir / "img.exr");
        EXPECT_EQ(runShell(smallRender(dir, c.extra)), c.code) << readText(dir / "err.txt");
        EXPECT_NE(readText(dir / "err.txt").find(c.says), std::string::npos) << readText(dir / "err.txt");
        EXPECT_EQ(fs::exists(dir / "img.exr"), c.code == 0);
    }
    EXPECT_EQ(readText(dir / "plain.txt"), "a file");

    // Stats over the job file itself (a copy): refused, the job untouched.
    fs::copy_file(std::string(CLIPBLUR_SOURCE_DIR) + "/configs/default.yaml", dir / "job.yaml");
    const std::string job = readText(dir / "job.yaml");
    EXPECT_EQ(runShell(smallRender(dir, out + " --stats " + (dir / "job.yaml").string(), (dir / "job.yaml").string())), 5);
    EXPECT_NE(readText(dir / "err.txt").find("would overwrite the input"), std::string::npos) << readText(dir / "err.txt");
    EXPECT_EQ(readText(dir / "job.yaml"), job);
    EXPECT_FALSE(fs::exists(dir / "img.exr"));
}

TEST(ExitCodes, JobAndSceneErrorsOfValidateAndRender) {
    const fs::path dir = testDir();
    const std::string validate = std::string(CLIPBLUR_BINARY) + " validate ";
    const std::string quiet = " > " + (dir / "out.txt").string() + " 2> " + (dir / "err.txt").string();
    EXPECT_EQ(runShell(validate + (dir / "missing.yaml").string() + quiet), 3);
    EXPECT_EQ(runShell(validate + objJob(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").string() + quiet), 0);
    const std::vector<std::pair<std::string, std::string>> bad_objs{
        {"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "mesh.obj:2:3: 'nan' is not a finite number"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "mesh.obj:4:7: vertex index 4 does not exist"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "mesh.obj:4:1: a face needs at least 3 vertices"},
    };
    for (const auto& [text, says] : bad_objs) {
        for (const std::string& command : {validate, std::string(CLIPBLUR_BINARY) + " render --out " +
                                                         (dir / "o.exr").string() + " "}) {
            SCOPED_TRACE(command + text);
            EXPECT_EQ(runShell(command + objJob(dir, text).string() + quiet), 4);
            EXPECT_NE(readText(dir / "err.txt").find(says), std::string::npos) << readText(dir / "err.txt");
            EXPECT_FALSE(fs::exists(dir / "o.exr"));
        }
    }
}

}  // namespace clipblur
