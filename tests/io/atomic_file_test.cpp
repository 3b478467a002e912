#include <fstream>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "scene/error.h"
#include "tests/support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

static std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    return {std::istreambuf_iterator<char>(in), {}};
}

TEST(AtomicFile, FailedWriteKeepsPreviousOutputAndLeavesNoTemporary) {
    const fs::path dir = testing::freshTempDir("clipblur_atomic_test");
    const fs::path target = dir / "out.txt";
    writeAtomically(target, [](const fs::path& tmp) { std::ofstream(tmp) << "first"; });
    EXPECT_EQ(slurp(target), "first");

    EXPECT_THROW(writeAtomically(target,
                                 [](const fs::path& tmp) {
                                     std::ofstream(tmp) << "half-writ";
                                     throw Error(ExitCode::Render, "interrupted");
                                 }),
                 Error);
    EXPECT_EQ(slurp(target), "first");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    fs::remove_all(dir);
}

// Issue 24, kind 5: a frame's files are replaced together. A write failing after others succeeded,
// or a group given up before commit, leaves every target as it was and no temporary.
TEST(AtomicFileGroup, NothingMovesUnlessEveryWriteSucceeded) {
    const fs::path dir = testing::freshTempDir("clipblur_atomic_group_test");
    const auto put = [](const char* text) { return [text](const fs::path& tmp) { std::ofstream(tmp) << text; }; };
    writeAtomically(dir / "a", put("a1"));
    writeAtomically(dir / "b", put("b1"));
    for (int failing = 0; failing < 3; ++failing) {
        SCOPED_TRACE(failing);
        AtomicFileGroup group;
        const auto step = [&](int i, const fs::path& target, const char* text) {
            group.write(target, [&, i, text](const fs::path& tmp) {
                std::ofstream(tmp) << text;
                if (i == failing) throw Error(ExitCode::Output, "disk full");
            });
        };
        EXPECT_THROW({
            step(0, dir / "a", "a2");
            step(1, dir / "b", "b2");
            step(2, dir / "c", "c2");
        }, Error);
        EXPECT_EQ(slurp(dir / "a"), "a1");
        EXPECT_EQ(slurp(dir / "b"), "b1");
    }
    {
        AtomicFileGroup abandoned;
        abandoned.write(dir / "a", put("a3"));
    }
    EXPECT_EQ(slurp(dir / "a"), "a1");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2) << "only a and b";

    AtomicFileGroup group;
    group.write(dir / "a", put("a4"));
    group.write(dir / "new" / "c", put("c4"));
    EXPECT_EQ(slurp(dir / "a"), "a1") << "nothing moves before commit";
    group.commit();
    EXPECT_EQ(slurp(dir / "a"), "a4");
    EXPECT_EQ(slurp(dir / "new" / "c"), "c4");
    fs::remove_all(dir);
}

// A target that became a folder after the pre-render checks: commit refuses before moving anything.
TEST(AtomicFileGroup, CommitRefusesAFolderTargetBeforeMovingAny) {
    const fs::path dir = testing::freshTempDir("clipblur_atomic_group_folder");
    writeAtomically(dir / "a", [](const fs::path& tmp) { std::ofstream(tmp) << "a1"; });
    AtomicFileGroup group;
    group.write(dir / "a", [](const fs::path& tmp) { std::ofstream(tmp) << "a2"; });
    group.write(dir / "b", [](const fs::path& tmp) { std::ofstream(tmp) << "b2"; });
    fs::create_directories(dir / "b");
    EXPECT_THROW(group.commit(), Error);
    EXPECT_EQ(slurp(dir / "a"), "a1");
    fs::remove_all(dir);
}

}  // namespace clipblur
