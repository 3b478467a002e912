#include <map>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "renderer/tiles.h"
#include "renderer/visibility/candidates.h"
#include "renderer/visibility/embree_scene.h"
#include "renderer/visibility/frame_geometry.h"
#include "scene/camera.h"
#include "scene/primitives.h"

namespace clipblur {

namespace {

// A UV sphere of `segments` (about segments^2 triangles) filling most of a 256 x 256 film, translating
// during the shutter so Embree traces a time-stepped (motion-blurred) scene as the renderer does.
// Building Embree's BVH and the projected frame for a million triangles takes seconds, so each size is
// built once per process and shared by every benchmark run on it.
struct SphereFixture {
    static constexpr int kFilm = 256;
    static constexpr int kTile = 32;  // RenderSettings::tile_size default

    Scene scene;
    EmbreeDevice device;
    Projection projection{kFilm, kFilm, 40.0};
    TileGrid grid{kFilm, kFilm, kTile};
    std::unique_ptr<EmbreeScene> embree;
    std::unique_ptr<FrameGeometry> frame;
    std::unique_ptr<MeshAdjacency> adjacency;
    std::vector<int> busy_tiles;  // tiles with at least one binned triangle: the only ones with work

    explicit SphereFixture(int segments) {
        scene.film.width = kFilm;
        scene.film.height = kFilm;
        scene.camera.vfov_degrees = 40.0;
        scene.camera.keys.push_back(CameraKey{0.0, glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0)});
        scene.materials.push_back(Material{});
        Object sphere;
        sphere.name = "sphere";
        sphere.mesh = makeSphere(1.0, segments);
        sphere.transform = {TransformKey{0.0, glm::dvec3(0, 0, 3.2)}, TransformKey{1.0, glm::dvec3(0.2, 0, 3.2)}};
        scene.objects.push_back(std::move(sphere));
        const FrameMotion motion(scene, 0.0, 1.0);
        embree = std::make_unique<EmbreeScene>(device, motion);
        frame = std::make_unique<FrameGeometry>(motion, projection, 0.0, grid);
        adjacency = std::make_unique<MeshAdjacency>(scene);
        for (int t = 0; t < grid.count(); ++t)
            if (!frame->tileTriangles(t).empty()) busy_tiles.push_back(t);
    }

    static const SphereFixture& get(int segments) {
        static std::map<int, std::unique_ptr<SphereFixture>> built;
        auto& slot = built[segments];
        if (!slot) slot = std::make_unique<SphereFixture>(segments);
        return *slot;
    }
};

// One findCandidates call per iteration, cycling over the tiles the sphere covers.
// Args: sphere segments, visibility rays per pixel side (0 = exhaustive binning, no rays).
void BM_FindCandidates(benchmark::State& state) {
    const SphereFixture& f = SphereFixture::get(static_cast<int>(state.range(0)));
    const int rays_per_side = static_cast<int>(state.range(1));
    CandidateScratch scratch;
    CandidateStats stats;
    std::size_t i = 0;
    for (auto _ : state) {
        const int index = f.busy_tiles[i++ % f.busy_tiles.size()];
        const std::vector<std::uint32_t> out =
            findCandidates(*f.frame, {*f.embree, *f.adjacency, rays_per_side}, index, scratch, stats);
        benchmark::DoNotOptimize(out.data());
    }
    const double tiles = static_cast<double>(state.iterations());
    state.counters["mesh_tris"] = static_cast<double>(f.frame->meshTriangles());
    state.counters["rays/s"] = benchmark::Counter(static_cast<double>(stats.rays), benchmark::Counter::kIsRate);
    // The tile's binned (exhaustive) screen triangles narrowed per second: the work the rays replace.
    state.counters["tris/s"] = benchmark::Counter(static_cast<double>(stats.binned), benchmark::Counter::kIsRate);
    state.counters["tiles/s"] = benchmark::Counter(tiles, benchmark::Counter::kIsRate);
    state.counters["binned/tile"] = static_cast<double>(stats.binned) / tiles;
    state.counters["hits/tile"] = static_cast<double>(stats.hit_triangles) / tiles;
    state.counters["cand/tile"] = static_cast<double>(stats.candidates) / tiles;
}
// 318 segments: 100,488 triangles; 1000 segments: 998,000 triangles.
BENCHMARK(BM_FindCandidates)
    ->ArgsProduct({{318, 1000}, {1, 2, 4, 0}})
    ->ArgNames({"segments", "rays"})
    ->MinTime(0.3)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

}  // namespace clipblur
