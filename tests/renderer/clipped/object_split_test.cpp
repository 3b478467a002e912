#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/render.h"
#include "renderer/test_scenes.h"
#include "support/motion_scenes.h"

namespace clipblur {

namespace {

using test::squareFilmJob;
using test::worldAtRaster;

// The triangles of `object` whose entry in `part` is p, as an object of their own with the same keys and
// material: the same surface moving the same way, with only the vertices it uses.
Object piece(const Object& object, const std::vector<int>& part, int p) {
    Object out = object;
    out.mesh.positions.clear();
    out.mesh.triangles.clear();
    for (DeformationKey& key : out.deformation) key.positions.clear();
    std::map<std::uint32_t, std::uint32_t> index;
    for (std::size_t t = 0; t < object.mesh.triangles.size(); ++t) {
        if (part[t] != p) continue;
        std::array<std::uint32_t, 3> triangle{};
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = object.mesh.triangles[t][static_cast<std::size_t>(k)];
            const auto [it, added] = index.emplace(v, static_cast<std::uint32_t>(out.mesh.positions.size()));
            if (added) {
                out.mesh.positions.push_back(object.mesh.positions[v]);
                for (std::size_t d = 0; d < out.deformation.size(); ++d)
                    out.deformation[d].positions.push_back(object.deformation[d].positions[v]);
            }
            triangle[static_cast<std::size_t>(k)] = it->second;
        }
        out.mesh.triangles.push_back(triangle);
    }
    return out;
}

// `object` cut into `parts` objects, triangle t going to part[t] (every part non-empty).
std::vector<Object> split(const Object& object, const std::vector<int>& part, int parts) {
    std::vector<Object> out;
    for (int p = 0; p < parts; ++p) out.push_back(piece(object, part, p));
    return out;
}

// A cells x cells board of quads at depth 10 filling most of a 48 x 48 film; cell (i, j) is triangles
// 2 (i cells + j) and the next.
Object board(int cells) {
    Object o;
    o.name = "board";
    const double step = 40.0 / cells;
    for (int i = 0; i <= cells; ++i)
        for (int j = 0; j <= cells; ++j) o.mesh.positions.push_back(worldAtRaster(4.0 + j * step, 4.0 + i * step, 10.0, 48));
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (cells + 1) + j); };
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {
            // Wound to face the camera (-z), as rasterQuad's.
            o.mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            o.mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        }
    return o;
}

// The paper's spin/pan (Table 1, case 4) over the board, sweep integration with automatic re-clips.
RenderJob spinPanJob(std::vector<Object> objects) {
    RenderJob job = squareFilmJob(48);
    job.render.method = Method::Clipped;
    job.render.time_integration = TimeIntegration::Sweep;
    Material black;
    black.base_color = glm::dvec3(0.0);
    job.scene.materials.push_back(black);
    job.scene.film.background = glm::dvec3(0.3);
    job.scene.camera.keys.push_back(CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(0, 0.1, 1), glm::dvec3(0.1, 1, 0)});
    job.scene.objects = std::move(objects);
    return job;
}

double maxDifference(const RenderResult& a, const RenderResult& b) {
    double worst = 0.0;
    for (const char* c : {"R", "G", "B", "A"}) {
        const auto& x = a.image.find(c)->values;
        const auto& y = b.image.find(c)->values;
        for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, double(std::abs(x[i] - y[i])));
    }
    return worst;
}

// What the split must not change: the re-clips and the positions (counts of the plan, not of objects).
void expectSameWork(const RenderResult& a, const RenderResult& b, const char* what) {
    const ClippedStats& x = a.stats.clipped();
    const ClippedStats& y = b.stats.clipped();
    EXPECT_EQ(x.segments, y.segments) << what;
    EXPECT_EQ(x.subframes_total, y.subframes_total) << what;
    EXPECT_EQ(x.subframes_max_per_tile, y.subframes_max_per_tile) << what;
    EXPECT_EQ(x.reclip.sweep_positions, y.reclip.sweep_positions) << what;
}

// Pixel values are float sums of the same fragments in another order: 1e-6, the tests' float tolerance.
constexpr double kFloatTolerance = 1e-6;

}  // namespace

// Issue 20's table: a still board under a turning camera, as 1 object, 2 (white and black cells) and one
// object per cell, must cost the same re-clips and give the same image. Nothing on it moves relative to
// anything else, so one re-clip serves, as it does for the one object.
TEST(ObjectSplit, StillBoardUnderATurningCameraCostsTheSameHoweverCut) {
    constexpr int kCells = 8;
    const Object whole = board(kCells);
    std::vector<int> colour(whole.mesh.triangles.size()), cell(whole.mesh.triangles.size());
    for (std::size_t t = 0; t < colour.size(); ++t) {
        const int c = static_cast<int>(t / 2);
        cell[t] = c;
        colour[t] = (c / kCells + c % kCells) % 2;
    }
    // Same material everywhere: the one object against one object per cell.
    const RenderResult one = renderFrame(spinPanJob({whole}), 0);
    const RenderResult cells = renderFrame(spinPanJob(split(whole, cell, kCells * kCells)), 0);
    EXPECT_EQ(one.stats.clipped().subframes_max_per_tile, 1);
    expectSameWork(one, cells, "1 against 64 objects");
    EXPECT_LE(maxDifference(one, cells), kFloatTolerance);

    // A checker: white and black cells as 2 objects against one object per cell, coloured alike.
    std::vector<Object> two = split(whole, colour, 2), many = split(whole, cell, kCells * kCells);
    two[1].material = 1;
    for (int c = 0; c < kCells * kCells; ++c) many[static_cast<std::size_t>(c)].material = (c / kCells + c % kCells) % 2;
    const RenderResult checker2 = renderFrame(spinPanJob(two), 0);
    const RenderResult checker64 = renderFrame(spinPanJob(many), 0);
    expectSameWork(one, checker2, "1 against 2 objects");
    expectSameWork(checker2, checker64, "2 against 64 objects");
    EXPECT_LE(maxDifference(checker2, checker64), kFloatTolerance);
}

// Seeded property: random moving scenes (camera keys inside the shutter, rigid and deforming objects),
// each rigid object cut into one object per triangle, render with the same work and image, with point
// subframes and with sweep integration.
TEST(ObjectSplit, RandomScenesCutIntoPiecesRenderAlike) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        Scene scene = testing::randomMovingScene(seed, 4);
        scene.film.width = 48;
        scene.film.height = 36;
        Scene cut = scene;
        cut.objects.clear();
        for (const Object& object : scene.objects) {
            if (!object.deformation.empty()) {  // a deforming object moves relative to its own pieces
                cut.objects.push_back(object);
                continue;
            }
            std::vector<int> part(object.mesh.triangles.size());
            for (std::size_t t = 0; t < part.size(); ++t) part[t] = static_cast<int>(t);
            for (Object& p : split(object, part, static_cast<int>(part.size()))) cut.objects.push_back(std::move(p));
        }
        ASSERT_GT(cut.objects.size(), scene.objects.size());
        for (const TimeIntegration integration : {TimeIntegration::Subframes, TimeIntegration::Sweep}) {
            RenderJob job;
            job.scene = scene;
            job.render.method = Method::Clipped;
            job.render.time_integration = integration;
            job.render.audit = true;
            RenderJob cut_job = job;
            cut_job.scene = cut;
            const RenderResult a = renderFrame(job, 0), b = renderFrame(cut_job, 0);
            const std::string what = "seed " + std::to_string(seed);
            expectSameWork(a, b, what.c_str());
            EXPECT_LE(maxDifference(a, b), kFloatTolerance) << what;
        }
    }
}

}  // namespace clipblur
