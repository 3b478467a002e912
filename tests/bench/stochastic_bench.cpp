#include <benchmark/benchmark.h>

#include "renderer/render.h"
#include "renderer/visibility/embree_scene.h"
#include "scene/camera.h"

namespace clipblur {

namespace {

// A 256 x 256 film filled by a grid of `cells` x `cells` quads (2 triangles each) at depth 5, translating
// and spinning during the shutter, lit by one directional light.
RenderJob gridJob(int cells, int samples) {
    RenderJob job;
    job.scene.film.width = 256;
    job.scene.film.height = 256;
    job.scene.camera.vfov_degrees = 60.0;
    job.scene.camera.keys.push_back(CameraKey{0.0, glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0)});
    job.scene.materials.push_back(Material{});
    job.scene.lights.push_back(Light{});
    Object grid;
    grid.name = "grid";
    for (int y = 0; y <= cells; ++y)
        for (int x = 0; x <= cells; ++x)
            grid.mesh.positions.push_back({-4.0 + 8.0 * x / cells, -4.0 + 8.0 * y / cells, 0.0});
    for (int y = 0; y < cells; ++y) {
        for (int x = 0; x < cells; ++x) {
            const auto i = static_cast<std::uint32_t>(y * (cells + 1) + x);
            const auto row = static_cast<std::uint32_t>(cells + 1);
            grid.mesh.triangles.push_back({i, i + 1, i + row + 1});
            grid.mesh.triangles.push_back({i, i + row + 1, i + row});
        }
    }
    grid.transform = {TransformKey{0.0, glm::dvec3(0, 0, 5)},
                      TransformKey{1.0, glm::dvec3(0.3, 0, 5), glm::angleAxis(0.2, glm::dvec3(0, 0, 1))}};
    job.scene.objects.push_back(grid);
    job.render.method = Method::Stochastic;
    job.render.samples = samples;
    return job;
}

void BM_StochasticFrame(benchmark::State& state) {
    const RenderJob job = gridJob(static_cast<int>(state.range(0)), 16);
    long long rays = 0;
    double steps = 0;
    for (auto _ : state) {
        const RenderResult r = renderFrame(job, 0);
        rays += r.stats.stochastic().rays();
        steps = static_cast<double>(r.stats.stochastic().max_time_steps);
    }
    state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
    state.counters["triangles"] = 2.0 * state.range(0) * state.range(0);
    state.counters["time_steps"] = steps;
}
BENCHMARK(BM_StochasticFrame)->Arg(16)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EmbreeSceneBuild(benchmark::State& state) {
    const RenderJob job = gridJob(static_cast<int>(state.range(0)), 1);
    const EmbreeDevice device;
    for (auto _ : state) {
        const EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 1.0));
        benchmark::DoNotOptimize(scene.get());
    }
    state.counters["triangles"] = 2.0 * state.range(0) * state.range(0);
}
BENCHMARK(BM_EmbreeSceneBuild)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

}  // namespace clipblur
