#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "renderer/fragments/fragment_tile.h"
#include "renderer/fragments/pixel_resolver.h"
#include "renderer/geometry/pixel_clip.h"

namespace clipblur {

namespace {

std::vector<ScreenTriangle> randomTriangles(int count, double size, double extent, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> centre(size, extent - size);
    std::uniform_real_distribution<double> u(-size, size);
    std::uniform_real_distribution<double> depth(0.1, 1.0);
    std::vector<ScreenTriangle> tris;
    while (int(tris.size()) < count) {
        ScreenTriangle t;
        const glm::dvec2 c(centre(rng), centre(rng));
        for (int k = 0; k < 3; ++k) {
            t.raster[k] = c + glm::dvec2(u(rng), u(rng));
            t.inv_depth[k] = depth(rng);
        }
        t.source = std::uint32_t(tris.size());
        t.layer = std::uint8_t(tris.size() % 2);
        if (validScreenTriangle(t)) tris.push_back(t);
    }
    return tris;
}

}  // namespace

// Exact clip of one triangle (about size x size px) to every pixel of its bounding box.
void BM_ClipTriangleToPixels(benchmark::State& state) {
    const double size = double(state.range(0));
    const auto tris = randomTriangles(1024, size, 4096.0, 1);
    long long pieces = 0;
    std::size_t i = 0;
    for (auto _ : state) {
        const ScreenTriangle& t = tris[i++ % tris.size()];
        const TriangleClipper clip(t.raster);
        const double y0 = std::floor(std::min({t.raster[0].y, t.raster[1].y, t.raster[2].y}));
        const double y1 = std::floor(std::max({t.raster[0].y, t.raster[1].y, t.raster[2].y}));
        const double x0 = std::floor(std::min({t.raster[0].x, t.raster[1].x, t.raster[2].x}));
        const double x1 = std::floor(std::max({t.raster[0].x, t.raster[1].x, t.raster[2].x}));
        for (double y = y0; y <= y1; ++y) {
            TriangleClipper::Piece strip;
            clip.clipToStrip(y, y + 1.0, strip);
            if (strip.poly.degenerate()) continue;
            for (double x = x0; x <= x1; ++x) {
                ConvexPolygon p;
                clip.clipToColumn(strip, x, x + 1.0, p);
                pieces += !p.degenerate();
                benchmark::DoNotOptimize(p);
            }
        }
    }
    state.counters["triangles/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["pieces/tri"] = double(pieces) / double(state.iterations());
}
BENCHMARK(BM_ClipTriangleToPixels)->Arg(1)->Arg(4)->Arg(16);

// Re-clip of one pixel's fragment union: n overlapping triangles (two layers) covering the pixel.
void BM_ResolvePixel(benchmark::State& state) {
    const int n = int(state.range(0));
    std::vector<std::vector<ScreenTriangle>> sets;
    for (int s = 0; s < 64; ++s) sets.push_back(randomTriangles(n, 1.2, 2.0, 100 + s));
    PixelResolver resolver;
    long long fragments = 0;
    std::size_t i = 0;
    for (auto _ : state) {
        const auto& tris = sets[i++ % sets.size()];
        resolver.reset(0, 0);
        for (const ScreenTriangle& t : tris) resolver.insert(t);
        fragments += static_cast<long long>(resolver.fragments().size());
    }
    state.counters["pixels/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["fragments/px"] = double(fragments) / double(state.iterations());
}
BENCHMARK(BM_ResolvePixel)->Arg(2)->Arg(8)->Arg(16);

// A 64x64 tile with 4096 random triangles of about 3 px: binning, front-to-back sort and resolve.
void BM_ResolveTile(benchmark::State& state) {
    const auto tris = randomTriangles(4096, 1.5, 64.0, 7);
    TileScratch scratch;
    FragmentTile tile;
    for (auto _ : state) {
        resolveTile(tris, PixelBounds::sized(0, 0, 64, 64), {}, scratch, tile);
        benchmark::DoNotOptimize(tile.fragments.data());
    }
    state.counters["pixels/s"] = benchmark::Counter(4096.0 * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["fragments/px"] = double(tile.fragments.size()) / 4096.0;
}
BENCHMARK(BM_ResolveTile);

}  // namespace clipblur
