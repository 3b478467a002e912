#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "renderer/propagation/blur_path_cases.h"
#include "renderer/propagation/vertex_ode.h"
#include "renderer/propagation/vertex_path.h"
#include "scene/error.h"

namespace clipblur::cli {

namespace {

struct PathsOptions {
    std::string case_name = "all";
    std::string method = "exact";
    int steps = 0;  // 0: one step per sample interval
    int samples = 20;
    double tolerance = 1e-10;
    bool convergence = false;
};

std::vector<BlurPathCase> selectedCases(const std::string& name) {
    if (name == "all") return blurPathCases();
    return {*findBlurPathCase(name)};
}

// One vertex's samples f = 0, 1/K, ..., 1; the ODE methods march from sample to sample.
std::vector<glm::dvec2> samplePath(const PathsOptions& o, const VertexPath& path) {
    std::vector<glm::dvec2> out;
    out.reserve(o.samples + 1);
    const VertexOde ode(path);
    glm::dvec3 y = ode.exactState(0.0);
    const int per_interval = o.steps / o.samples;
    for (int k = 0; k <= o.samples; ++k) {
        const double f = static_cast<double>(k) / o.samples;
        if (o.method == "exact") {
            out.push_back(path.at(f).p);
            continue;
        }
        if (k > 0) {
            const double f_prev = static_cast<double>(k - 1) / o.samples;
            if (o.method == "adaptive")
                y = integrateAdaptive(ode, f_prev, y, f, o.tolerance).y;
            else
                y = integrateFixed(ode, {o.method == "euler" ? OdeMethod::Euler : OdeMethod::Rk4, per_interval}, f_prev, y, f);
        }
        out.push_back({y.x, y.y});
    }
    return out;
}

int printPaths(const PathsOptions& o) {
    std::printf("case,x,y,f,p1,p2\n");
    const std::vector<double> grid = blurPathGrid();
    for (const BlurPathCase& c : selectedCases(o.case_name)) {
        const CameraMotion camera = c.cameraMotion();
        for (double x : grid)
            for (double y : grid) {
                const VertexPath path(camera, c.vertexStart(x, y), c.vertexEnd(x, y));
                const std::vector<glm::dvec2> ps = samplePath(o, path);
                for (int k = 0; k <= o.samples; ++k)
                    std::printf("%s,%g,%g,%.17g,%.17g,%.17g\n", std::string(c.name).c_str(), x, y,
                                static_cast<double>(k) / o.samples, ps[k].x, ps[k].y);
            }
    }
    return 0;
}

// Error at f = 1 (largest over the grid) against the exact path for a doubling ladder of step counts.
int printConvergence(const PathsOptions& o) {
    std::printf("case,method,steps,error\n");
    const std::vector<double> grid = blurPathGrid();
    for (const BlurPathCase& c : selectedCases(o.case_name)) {
        const CameraMotion camera = c.cameraMotion();
        for (const auto& [label, method] : {std::pair{"euler", OdeMethod::Euler}, std::pair{"rk4", OdeMethod::Rk4}})
            for (int steps = 1; steps <= 4096; steps *= 2) {
                double worst = 0.0;
                for (double x : grid)
                    for (double y : grid) {
                        const VertexOde ode(VertexPath(camera, c.vertexStart(x, y), c.vertexEnd(x, y)));
                        const glm::dvec3 end = integrateFixed(ode, {method, steps}, 0.0, ode.exactState(0.0), 1.0);
                        const glm::dvec3 exact = ode.exactState(1.0);
                        worst = std::max(worst, std::hypot(end.x - exact.x, end.y - exact.y));
                    }
                std::printf("%s,%s,%d,%.6e\n", std::string(c.name).c_str(), label, steps, worst);
            }
    }
    return 0;
}

}  // namespace

Action addPathsCommand(CLI::App& app) {
    auto opts = std::make_shared<PathsOptions>();
    CLI::App* sub = app.add_subcommand(
        "paths", "Print image-plane vertex paths of the paper's Table 1 cases as CSV (case,x,y,f,p1,p2)");
    std::vector<std::string> case_names{"all"};
    for (const BlurPathCase& c : blurPathCases()) case_names.emplace_back(c.name);
    sub->add_option("--case", opts->case_name, "Table 1 case")->check(CLI::IsMember(case_names));
    sub->add_option("--method", opts->method, "exact projection, or the ODE of eq. 11-12 (euler, rk4, adaptive RK4)")
        ->check(CLI::IsMember({"exact", "euler", "rk4", "adaptive"}));
    sub->add_option("--steps", opts->steps, "ODE steps over the frame, a multiple of --samples (default: --samples)")
        ->check(CLI::Range(1, 1 << 24));
    sub->add_option("--samples", opts->samples, "Output intervals K: rows at f = 0, 1/K, ..., 1")
        ->check(CLI::Range(1, 1 << 20));
    sub->add_option("--tolerance", opts->tolerance, "Per-step error tolerance of --method adaptive")
        ->check(CLI::PositiveNumber);
    sub->add_flag("--convergence", opts->convergence,
                  "Instead of paths, print case,method,steps,error: largest error at f = 1 for Euler and RK4");
    return [opts]() {
        if (opts->steps == 0) opts->steps = opts->samples;
        if (opts->steps % opts->samples != 0)
            throw Error(ExitCode::Usage, "--steps (" + std::to_string(opts->steps) +
                                             ") must be a multiple of --samples (" +
                                             std::to_string(opts->samples) + ")");
        return opts->convergence ? printConvergence(*opts) : printPaths(*opts);
    };
}

}  // namespace clipblur::cli
