#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "io/slurm_script.h"
#include "scene/error.h"
#include "tests/support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

static FarmPlan examplePlan(const fs::path& dir) {
    FarmPlan plan;
    plan.clipblur = dir / "bin" / "clipblur";
    plan.job_file = dir / "jobs" / "it's a $job.yaml";
    plan.overrides = {"film.width=64", "scene.name=a b \"c\" $HOME `x`"};
    plan.workdir = dir;
    plan.farm_dir = dir / "out" / ".clipblur-farm";
    plan.first_frame = 1;
    plan.last_frame = 2;
    plan.tiles = 4;
    return plan;
}

TEST(SlurmScript, ElementIdsMapFrameMajor) {
    const FarmPlan plan = examplePlan("/tmp");
    EXPECT_EQ(plan.elementCount(), 8);
    EXPECT_EQ(elementOf(plan, 0), (FarmElement{1, 0}));
    EXPECT_EQ(elementOf(plan, 5), (FarmElement{2, 1}));
    EXPECT_EQ(elementOf(plan, 7), (FarmElement{2, 3}));
    for (int id = 0; id < plan.elementCount(); ++id) {
        const FarmElement e = elementOf(plan, id);
        EXPECT_EQ(elementId(plan, e.frame, e.tile), id);
    }
    EXPECT_THROW(elementOf(plan, 8), Error);
    EXPECT_THROW(elementId(plan, 3, 0), Error);
    EXPECT_THROW(elementId(plan, 1, 4), Error);
}

TEST(SlurmScript, ArraySpecCollapsesRuns) {
    EXPECT_EQ(arraySpec({7, 1, 5, 2, 3, 3}), "1-3,5,7");
    EXPECT_EQ(arraySpec({0}), "0");
    EXPECT_EQ(arraySpec({4, 5}), "4-5");
    EXPECT_EQ(arraySpec({}), "");
}

static std::string runShell(const std::string& command) {
    std::FILE* pipe = ::popen(command.c_str(), "r");
    std::string out;
    char buf[256];
    while (std::fgets(buf, sizeof buf, pipe)) out += buf;
    ::pclose(pipe);
    return out;
}

// The shell itself is the oracle: printf must get back exactly the original word.
TEST(SlurmScript, ShellQuoteSurvivesTheShell) {
    for (const std::string word : {"plain", "it's", "a b", "$HOME", "`id`", "\"q\"", "back\\slash", "", "'''", "*"})
        EXPECT_EQ(runShell("printf %s " + shellQuote(word)), word) << word;
}

TEST(SlurmScript, RenderScriptListsOnlyGivenElements) {
    FarmPlan plan = examplePlan("/work/farm");
    plan.partition = "render";
    plan.cpus_per_task = 2;
    const std::string s = renderArrayScript(plan, {6, 0, 2, 1});
    EXPECT_NE(s.find("\n#SBATCH --array=0-2,6\n"), std::string::npos) << s;
    EXPECT_NE(s.find("\n#SBATCH --partition=render\n"), std::string::npos);
    EXPECT_NE(s.find("\n#SBATCH --cpus-per-task=2\n"), std::string::npos);
    EXPECT_NE(s.find("\n#SBATCH --output=/work/farm/out/.clipblur-farm/render-%A_%a.log\n"), std::string::npos);
    EXPECT_NE(s.find("\n#SBATCH --chdir=/work/farm\n"), std::string::npos);
    EXPECT_EQ(s.rfind("#!/bin/bash\n", 0), 0u);
    EXPECT_THROW(renderArrayScript(plan, {}), Error);
    EXPECT_THROW(renderArrayScript(plan, {8}), Error);
}

TEST(SlurmScript, DirectivePathWithSpaceIsRefused) {
    FarmPlan plan = examplePlan("/work/my farm");
    EXPECT_THROW(mergeScript(plan), Error);
}

class SlurmScriptRun : public ::testing::Test {
protected:
    void SetUp() override {
        // One folder per test: ctest runs the tests of this fixture in parallel processes.
        dir = testing::freshTempDir(std::string("clipblur_slurm_script_test_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir / "bin");
        plan = examplePlan(dir);
        // A stand-in binary that logs its argv one word per line; `merge --check` answers with $CHECK.
        std::ofstream(plan.clipblur) << "#!/bin/bash\n"
                                        "printf '%s\\n' \"$@\" >> \"" << (dir / "argv").string() << "\"\n"
                                        "echo --- >> \"" << (dir / "argv").string() << "\"\n"
                                        "if [ \"$1\" = merge ]; then exit \"${CHECK:-1}\"; fi\n";
        fs::permissions(plan.clipblur, fs::perms::owner_all);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::string runElement(const std::string& script, int id, int check) {
        const fs::path path = dir / "element.sh";
        std::ofstream(path) << script;
        fs::remove(dir / "argv");
        runShell("SLURM_ARRAY_TASK_ID=" + std::to_string(id) + " CHECK=" + std::to_string(check) + " bash " +
                 shellQuote(path.string()) + " > /dev/null");
        std::ifstream in(dir / "argv");
        return {std::istreambuf_iterator<char>(in), {}};
    }

    fs::path dir;
    FarmPlan plan;
};

// Element 5 of frames 1-2 x 4 tiles is frame 2, tile 1; every word must arrive intact.
TEST_F(SlurmScriptRun, ElementRunsRenderForItsFrameAndTile) {
    const std::string words = plan.job_file.string() + "\n--set\nfilm.width=64\n--set\n" + plan.overrides[1] + "\n";
    const std::string check = "merge\n" + words + "--frames\n2-2\n--tiles\n4\n--check\n--shard\n1\n---\n";
    const std::string render = "render\n" + words + "--frames\n2-2\n--tile\n1/4\n---\n";
    const std::string script = renderArrayScript(plan, {5});
    EXPECT_EQ(runElement(script, 5, 1), check + render);
    EXPECT_EQ(runElement(script, 5, 0), check);  // shard already complete: no render
}

TEST_F(SlurmScriptRun, MergeScriptMergesWholeRange) {
    const std::string argv = runElement(mergeScript(plan), 0, 0);
    EXPECT_EQ(argv, "merge\n" + plan.job_file.string() + "\n--set\nfilm.width=64\n--set\n" + plan.overrides[1] +
                        "\n--frames\n1-2\n--tiles\n4\n---\n");
}

TEST(SlurmScript, SbatchCommandCarriesDependency) {
    EXPECT_EQ(sbatchCommand("/f/render.sh"), (std::vector<std::string>{"sbatch", "--parsable", "/f/render.sh"}));
    EXPECT_EQ(sbatchCommand("/f/merge.sh", "123", true),
              (std::vector<std::string>{"sbatch", "--parsable", "--dependency=afterok:123", "--wait", "/f/merge.sh"}));
}

TEST(SlurmScript, ParsesSbatchParsableOutput) {
    EXPECT_EQ(parseSbatchJobId("42\n"), "42");
    EXPECT_EQ(parseSbatchJobId("42;cluster\n"), "42");
    EXPECT_EQ(parseSbatchJobId("sbatch: warning: something\n43\n"), "43");
    EXPECT_THROW(parseSbatchJobId(""), Error);
    EXPECT_THROW(parseSbatchJobId("Submitted batch job 5\n"), Error);
}

}  // namespace clipblur
