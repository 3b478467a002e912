#include "renderer/integrate/window_sums.h"

#include <algorithm>

#include "renderer/parallel_time.h"

namespace clipblur {

WindowSums::WindowSums(std::size_t pixels, bool with_objects) {
    parallelInvoke([&] { colour.resize(pixels); }, [&] { covered.resize(pixels); }, [&] { depth.resize(pixels); },
                   [&] { motion.resize(pixels); }, [&] { objects.resize(with_objects ? pixels : 0); },
                   [&] { levels.assign(pixels, LevelDifference(0.0f)); });
}

void WindowSums::add(std::size_t i, double scale, const Spill& s) {
    colour[i] += scale * s.colour;
    covered[i] += scale * s.covered;
    depth[i] += scale * s.depth;
    motion[i] += scale * s.motion;
    if (!objects.empty()) addShares(objects[i], s.objects, scale);
    levels[i] += static_cast<float>(scale) * s.level;
}

void WindowSums::addStill(std::size_t i, double scale, const PixelSums& still, std::size_t p) {
    colour[i] += scale * still.colour[p];
    covered[i] += scale * still.covered[p];
    depth[i] += scale * still.depth[p];
    motion[i] += scale * glm::dvec2(0.0);
    if (!objects.empty() && !still.objects.empty()) addShares(objects[i], still.objects[p], scale);
}

void WindowSums::addPixel(std::size_t i, const WindowSums& other) {
    colour[i] += other.colour[i];
    covered[i] += other.covered[i];
    depth[i] += other.depth[i];
    motion[i] += other.motion[i];
    if (!objects.empty() && !other.objects.empty()) addShares(objects[i], other.objects[i], 1.0);
    levels[i] += other.levels[i];
}

void WindowSums::clearPixel(std::size_t i) {
    colour[i] = glm::dvec3(0.0);
    covered[i] = 0.0;
    depth[i] = 0.0;
    motion[i] = glm::dvec2(0.0);
    if (!objects.empty()) objects[i].clear();
    levels[i] = LevelDifference(0.0f);
}

void addSpills(std::vector<std::vector<Spill>>& spills, const PixelBounds& window, int band_rows, WindowSums& target) {
    const std::size_t band = static_cast<std::size_t>(band_rows) * static_cast<std::size_t>(window.width());
    if (band == 0) return;  // an empty window
    const auto bands = static_cast<int>((window.area() + band - 1) / band);
    parallelFor(0, bands, [&](int b) {
        const std::size_t begin = static_cast<std::size_t>(b) * band, end = begin + band;
        for (const auto& tile_spills : spills) {
            auto s = std::lower_bound(tile_spills.begin(), tile_spills.end(), begin,
                                      [](const Spill& spill, std::size_t i) { return spill.out < i; });
            for (; s != tile_spills.end() && s->out < end; ++s) target.add(s->out, 1.0, *s);
        }
    });
    parallelFor(std::size_t(0), spills.size(), [&](std::size_t t) { std::vector<Spill>().swap(spills[t]); });
}

}  // namespace clipblur
