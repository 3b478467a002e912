#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "renderer/propagation/subframes.h"
#include "renderer/propagation/surface_path.h"

namespace clipblur {
namespace {

// A camera that pans and spins, and a rotating, translating object with a few hundred triangles.
Scene benchScene() {
    Scene scene;
    scene.film = {640, 360, glm::dvec3(0.0)};
    scene.camera.keys = {{0.0, {0, 0, -10}, {0, 0, 1}, {0, 1, 0}}, {1.0, {0.5, 0, -10}, {0, 0.1, 1}, {0.1, 1, 0}}};
    scene.materials.emplace_back();
    Object object;
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 600; ++i) object.mesh.positions.emplace_back(u(rng), u(rng), u(rng));
    for (std::uint32_t i = 0; i + 2 < 600; i += 3) object.mesh.triangles.push_back({i, i + 1, i + 2});
    object.transform = {{0.0, {0, 0, 0}, {1, 0, 0, 0}, glm::dvec3(1.0)},
                        {1.0, {1, 0, 0}, glm::angleAxis(0.5, glm::normalize(glm::dvec3(1, 1, 0))), glm::dvec3(1.0)}};
    scene.objects.push_back(std::move(object));
    return scene;
}

std::vector<MeshPoint> benchPoints(const Scene& scene, int count) {
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<MeshPoint> points;
    const auto triangles = static_cast<std::uint32_t>(scene.objects[0].mesh.triangles.size());
    for (int i = 0; i < count; ++i) {
        glm::dvec3 b(u(rng), u(rng), u(rng));
        points.push_back({0, static_cast<std::uint32_t>(i) % triangles, b / (b.x + b.y + b.z)});
    }
    return points;
}

void BM_ProjectSurfacePoint(benchmark::State& state) {
    const Scene scene = benchScene();
    const Projection proj(640, 360, 40.0);
    const MotionSnapshot snapshot(scene, proj, 0.37);
    const auto points = benchPoints(scene, 4096);
    for (auto _ : state)
        for (const MeshPoint& p : points) benchmark::DoNotOptimize(project(snapshot, scene, p));
    state.SetItemsProcessed(state.iterations() * static_cast<long long>(points.size()));
}
BENCHMARK(BM_ProjectSurfacePoint);

void BM_ProjectMotion(benchmark::State& state) {
    const Scene scene = benchScene();
    const Projection proj(640, 360, 40.0);
    const MotionSnapshot snapshot(scene, proj, 0.37);
    const auto points = benchPoints(scene, 4096);
    for (auto _ : state)
        for (const MeshPoint& p : points) benchmark::DoNotOptimize(projectMotion(snapshot, scene, p));
    state.SetItemsProcessed(state.iterations() * static_cast<long long>(points.size()));
}
BENCHMARK(BM_ProjectMotion);

void BM_MeasureTriangleFragment(benchmark::State& state) {
    const Scene scene = benchScene();
    const Projection proj(640, 360, 40.0);
    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    const auto points = benchPoints(scene, 3 * 256);
    for (auto _ : state)
        for (std::size_t i = 0; i < points.size(); i += 3)
            benchmark::DoNotOptimize(sampler.measure(std::span(points).subspan(i, 3)));
    state.SetItemsProcessed(state.iterations() * static_cast<long long>(points.size() / 3));
}
BENCHMARK(BM_MeasureTriangleFragment);

}  // namespace
}  // namespace clipblur
