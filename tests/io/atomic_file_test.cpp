#include <fstream>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "scene/error.h"

namespace clipblur {

namespace fs = std::filesystem;

static std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    return {std::istreambuf_iterator<char>(in), {}};
}

TEST(AtomicFile, FailedWriteKeepsPreviousOutputAndLeavesNoTemporary) {
    const fs::path dir = fs::temp_directory_path() / "clipblur_atomic_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
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

}  // namespace clipblur
