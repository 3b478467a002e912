#include <array>
#include <cstdio>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include <gtest/gtest.h>

namespace clipblur {
namespace {

struct CommandRun {
    int exit_code = -1;
    std::string out;
};

CommandRun runClipblur(const std::string& args) {
    const std::string cmd = std::string(CLIPBLUR_BINARY) + " " + args + " 2>/dev/null";
    CommandRun run;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return run;
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) run.out.append(buf.data(), n);
    const int status = pclose(pipe);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

TEST(PathsCommand, PrintsOneRowPerVertexAndSample) {
    const CommandRun r = runClipblur("paths --case pan --samples 4");
    ASSERT_EQ(r.exit_code, 0);
    std::istringstream in(r.out);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "case,x,y,f,p1,p2");
    int rows = 0;
    std::string last;
    while (std::getline(in, line)) ++rows, last = line;
    EXPECT_EQ(rows, 11 * 11 * 5);
    // The last vertex (20, 20) at f = 1: see BlurPathCases.PanFollowsTheTangentLaw for the formula.
    double x, y, f, p1, p2;
    ASSERT_EQ(std::sscanf(last.c_str(), "pan,%lf,%lf,%lf,%lf,%lf", &x, &y, &f, &p1, &p2), 5);
    EXPECT_EQ(f, 1.0);
    EXPECT_NEAR(p1, (2.0 - 0.1) / (1.0 + 2.0 * 0.1), 1e-14);
}

TEST(PathsCommand, OdeMethodsAgreeWithExact) {
    const CommandRun exact = runClipblur("paths --case recede_spin_pan --samples 2");
    const CommandRun rk4 = runClipblur("paths --case recede_spin_pan --samples 2 --method adaptive --tolerance 1e-12");
    ASSERT_EQ(exact.exit_code, 0);
    ASSERT_EQ(rk4.exit_code, 0);
    std::istringstream a(exact.out), b(rk4.out);
    std::string la, lb;
    int rows = 0;
    while (std::getline(a, la) && std::getline(b, lb)) {
        if (rows++ == 0) continue;
        double xa, ya, fa, p1a, p2a, xb, yb, fb, p1b, p2b;
        ASSERT_EQ(std::sscanf(la.c_str(), "recede_spin_pan,%lf,%lf,%lf,%lf,%lf", &xa, &ya, &fa, &p1a, &p2a), 5);
        ASSERT_EQ(std::sscanf(lb.c_str(), "recede_spin_pan,%lf,%lf,%lf,%lf,%lf", &xb, &yb, &fb, &p1b, &p2b), 5);
        // Per-step tolerance 1e-12 over a few tens of steps.
        EXPECT_NEAR(p1a, p1b, 1e-10);
        EXPECT_NEAR(p2a, p2b, 1e-10);
    }
    EXPECT_EQ(rows, 1 + 121 * 3);
}

TEST(PathsCommand, BadArgumentsAreUsageErrors) {
    EXPECT_EQ(runClipblur("paths --case tumble").exit_code, 2);
    EXPECT_EQ(runClipblur("paths --method midpoint").exit_code, 2);
    EXPECT_EQ(runClipblur("paths --samples 0").exit_code, 2);
    EXPECT_EQ(runClipblur("paths --samples 20 --steps 30 --method rk4").exit_code, 2);
    EXPECT_EQ(runClipblur("paths --tolerance -1 --method adaptive").exit_code, 2);
}

TEST(PathsCommand, ConvergenceTableHasBothMethods) {
    const CommandRun r = runClipblur("paths --convergence --case spin");
    ASSERT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("spin,euler,1024,"), std::string::npos);
    EXPECT_NE(r.out.find("spin,rk4,16,"), std::string::npos);
}

}  // namespace
}  // namespace clipblur
