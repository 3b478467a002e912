#include <vector>

#include <benchmark/benchmark.h>

#include "renderer/propagation/blur_path_cases.h"
#include "renderer/propagation/vertex_ode.h"
#include "renderer/propagation/vertex_path.h"

namespace clipblur {
namespace {

std::vector<VertexPath> table1Paths() {
    const BlurPathCase c = *findBlurPathCase("recede_spin_pan");
    const CameraMotion camera = c.cameraMotion();
    std::vector<VertexPath> paths;
    for (int copy = 0; copy < 8; ++copy)
        for (double x : blurPathGrid())
            for (double y : blurPathGrid())
                paths.emplace_back(camera, c.vertexStart(x + 0.1 * copy, y), c.vertexEnd(x + 0.1 * copy, y));
    return paths;
}

// The renderer's pattern: every vertex propagated to one subframe f, the rotation Q(f) shared.
void BM_ExactPathSharedSubframe(benchmark::State& state) {
    const std::vector<VertexPath> paths = table1Paths();
    double f = 0.0;
    for (auto _ : state) {
        f = f < 1.0 ? f + 1.0 / 64.0 : 0.0;
        const glm::dmat3 q = paths.front().rotation().at(f);
        for (const VertexPath& path : paths) {
            const ImagePoint ip = path.at(q, f);
            benchmark::DoNotOptimize(ip);
        }
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(paths.size()));
}
BENCHMARK(BM_ExactPathSharedSubframe);

// One vertex at its own time: the rotation (one sincos) is recomputed per evaluation.
void BM_ExactPathOwnTime(benchmark::State& state) {
    const std::vector<VertexPath> paths = table1Paths();
    double f = 0.0;
    for (auto _ : state) {
        for (const VertexPath& path : paths) {
            f = f < 1.0 ? f + 0.0078125 : 0.0;
            const ImagePoint ip = path.at(f);
            benchmark::DoNotOptimize(ip);
        }
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(paths.size()));
}
BENCHMARK(BM_ExactPathOwnTime);

// RK4 on eq. 11-12, 20 steps per frame as in `clipblur paths --method rk4`: items are positions (steps).
void BM_Rk4Path(benchmark::State& state) {
    const std::vector<VertexPath> paths = table1Paths();
    std::vector<VertexOde> odes(paths.begin(), paths.end());
    const int steps = 20;
    for (auto _ : state) {
        for (const VertexOde& ode : odes) {
            const glm::dvec3 y = integrateFixed(ode, {OdeMethod::Rk4, steps}, 0.0, ode.exactState(0.0), 1.0);
            benchmark::DoNotOptimize(y);
        }
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(odes.size()) * steps);
}
BENCHMARK(BM_Rk4Path);

}  // namespace
}  // namespace clipblur
