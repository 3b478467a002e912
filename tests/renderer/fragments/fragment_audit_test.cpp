#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/fragments/fragment_audit.h"
#include "tests/renderer/fragments/fragment_test_util.h"

namespace clipblur {

namespace {

FragmentTile resolved(const std::vector<ScreenTriangle>& tris, const PixelBounds& rect) {
    TileScratch scratch;
    FragmentTile tile;
    resolveTile(tris, rect, {}, scratch, tile);
    return tile;
}

// Random triangles a few pixels across at random slanted depths: overlaps, interpenetration and
// coincident layers (every third triangle gets a frame-1 copy with 1e-9 relative depth noise).
std::vector<ScreenTriangle> randomScene(std::uint64_t seed, int count) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> pos(-1.0, 9.0), slope(-0.05, 0.05), depth(0.2, 1.0);
    std::vector<ScreenTriangle> tris;
    for (int i = 0; i < count; ++i) {
        const testing::Plane w{slope(rng), slope(rng), depth(rng)};
        ScreenTriangle t = testing::makeTriangle({pos(rng), pos(rng)}, {pos(rng), pos(rng)}, {pos(rng), pos(rng)}, w,
                                                 std::uint32_t(tris.size()));
        if (!validScreenTriangle(t)) continue;
        tris.push_back(t);
        if (i % 3 == 0) {
            ScreenTriangle copy = t;
            for (double& d : copy.inv_depth) d *= 1.0 + 1e-9;
            copy.layer = 1;
            copy.source = std::uint32_t(tris.size());
            tris.push_back(copy);
        }
    }
    return tris;
}

}  // namespace

// The resolver's output passes the audit on random scenes: the audit is the oracle the renderer runs on
// every test render, so it must not cry wolf on correct tiles.
TEST(FragmentAudit, AcceptsResolvedRandomTiles) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        const auto tris = randomScene(seed, 12);
        const FragmentTile tile = resolved(tris, PixelBounds::sized(0, 0, 8, 8));
        AuditStats stats;
        auditTile(tris, tile, stats);
        EXPECT_EQ(stats.violations, 0) << "seed " << seed << ": " << stats.first_violation;
        EXPECT_EQ(stats.pixels, 64);
        EXPECT_EQ(stats.union_pixels, 64);
        // Observed worst values are ~1e-16; the tolerance (1e-9) is the bound, not the expectation.
        EXPECT_LT(stats.worst_coverage, 1e-12);
        EXPECT_LT(stats.worst_overlap, 1e-12);
    }
}

// The union area against hand-computed coverage: two overlapping axis-aligned squares in pixel (3, 2).
TEST(FragmentAudit, UnionCoverageMatchesAnalyticArea) {
    const testing::Plane near{0, 0, 1.0}, far{0, 0, 0.5};
    auto tris = testing::makeQuad(3.1, 2.2, 3.6, 2.9, near, 0);
    for (const auto& t : testing::makeQuad(3.4, 2.5, 4.5, 3.5, far, 2)) tris.push_back(t);
    // Union inside the pixel: 0.5*0.7 + 0.6*0.5 - 0.2*0.4 = 0.57.
    FragmentTile tile = resolved(tris, PixelBounds::sized(3, 2, 1, 1));
    AuditStats stats;
    auditTile(tris, tile, stats);
    EXPECT_EQ(stats.violations, 0) << stats.first_violation;
    double sum = 0.0;
    for (const Fragment& f : tile.pixel(3, 2)) sum += f.area;
    EXPECT_NEAR(sum, 0.57, 1e-12);

    // A tile claiming 0.1 px^2 too little coverage (one fragment lost) must be caught.
    FragmentTile lost = tile;
    lost.fragments.pop_back();
    lost.offsets.back() -= 1;
    AuditStats caught;
    auditTile(tris, lost, caught);
    EXPECT_GT(caught.violations, 0);
    EXPECT_GT(caught.worst_coverage, 1e-3);
}

TEST(FragmentAudit, CatchesOverlapOutsideAndWrongVisibility) {
    const testing::Plane near{0, 0, 1.0}, far{0, 0, 0.5};
    auto tris = testing::makeQuad(0.0, 0.0, 1.0, 1.0, far, 0);
    for (const auto& t : testing::makeQuad(0.25, 0.25, 0.75, 0.75, near, 2)) tris.push_back(t);
    const FragmentTile good = resolved(tris, PixelBounds::sized(0, 0, 1, 1));
    AuditStats ok;
    auditTile(tris, good, ok);
    ASSERT_EQ(ok.violations, 0) << ok.first_violation;

    // Overlap: duplicate a fragment (also breaks the covered-area sum).
    FragmentTile twice = good;
    twice.fragments.push_back(twice.fragments.front());
    twice.offsets.back() += 1;
    AuditStats overlap;
    auditTile(tris, twice, overlap);
    EXPECT_GT(overlap.worst_overlap, 1e-3);
    EXPECT_NE(overlap.first_violation.find("pixel (0, 0)"), std::string::npos);

    // Outside: move one vertex out of the pixel by 0.01 px.
    FragmentTile out = good;
    out.fragments.front().vertices[0].x -= 0.01 + out.fragments.front().vertices[0].x;
    AuditStats outside;
    auditTile(tris, out, outside);
    EXPECT_NEAR(outside.worst_outside, 0.01, 1e-12);
    EXPECT_GT(outside.violations, 0);

    // Visibility: the far quad drawn where the near one should win. Swap depths of the inputs only, so the
    // geometry stays a valid partition and only the depth order is wrong.
    auto swapped = tris;
    for (auto& t : swapped) t.inv_depth = {1.5 - t.inv_depth[0], 1.5 - t.inv_depth[1], 1.5 - t.inv_depth[2]};
    AuditStats wrong;
    auditTile(swapped, good, wrong);
    EXPECT_GT(wrong.violations, 0);
    EXPECT_NE(wrong.first_violation.find("nearer"), std::string::npos) << wrong.first_violation;
}

namespace {

ScreenTriangle tri(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, std::array<double, 3> w, std::uint32_t source,
                   std::uint8_t layer) {
    ScreenTriangle t;
    t.raster = {a, b, c};
    t.inv_depth = w;
    t.source = source;
    t.layer = layer;
    return t;
}

void expectCleanPixel(const std::vector<ScreenTriangle>& tris, int x, int y) {
    TileScratch scratch;
    FragmentTile tile;
    resolveTile(tris, PixelBounds::sized(x, y, 1, 1), {}, scratch, tile);
    AuditStats stats;
    auditTile(tris, tile, stats);
    EXPECT_EQ(stats.violations, 0) << stats.first_violation;
    EXPECT_LT(stats.worst_overlap, 1e-12);
}

}  // namespace

// Pixels where the audit caught overlapping fragments in test renders (inputs printed to 17 digits).
// Crossing points rounded into a tiny concavity: a cluster of nearly equal vertices whose edge lines
// have arbitrary directions and cut through the piece (fixed by skipping such edges: supportingEdge).
// Here a quad's frame-0 and frame-1 copies propagated to one subframe (1/z 0.25) over a background grid
// (0.1); the background leaked under the quad (coverage 1.00017 px^2).
TEST(FragmentAudit, PropagatedQuadOverBackgroundRegression) {
    expectCleanPixel({
        tri({14.31818181818182, 11.954545454545457}, {14.31818181818182, 18.454545454545457}, {9.9848484848484844, 11.954545454545457}, {0.25, 0.25, 0.25}, 28, 0),
        tri({9.9848484848484844, 11.954545454545457}, {14.31818181818182, 18.454545454545457}, {14.31818181818182, 19.954545454545457}, {0.25, 0.25, 0.25}, 29, 0),
        tri({9.9848484848484844, 11.954545454545457}, {14.31818181818182, 19.954545454545457}, {9.3181818181818166, 19.954545454545457}, {0.25, 0.25, 0.25}, 30, 0),
        tri({9.3181818181818166, 10.954545454545453}, {13.318181818181818, 10.954545454545453}, {13.318181818181817, 14.954545454545453}, {0.25, 0.25, 0.24999999999999994}, 103, 1),
        tri({9.3181818181818166, 10.954545454545453}, {13.318181818181817, 14.954545454545453}, {11.984848484848483, 14.954545454545455}, {0.25, 0.24999999999999994, 0.25000000000000006}, 104, 1),
        tri({9.3181818181818166, 10.954545454545453}, {11.984848484848484, 14.954545454545455}, {9.3181818181818166, 14.954545454545455}, {0.25, 0.25, 0.25}, 105, 1),
        tri({11, 14.000000000000002}, {10, 14}, {10, 13}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 164, 1),
        tri({11, 14.000000000000002}, {10, 13}, {11.000000000000002, 13.000000000000002}, {0.10000000000000001, 0.10000000000000001, 0.099999999999999978}, 165, 1),
        tri({12, 14}, {11, 14.000000000000002}, {11.000000000000002, 13.000000000000002}, {0.10000000000000001, 0.10000000000000001, 0.099999999999999978}, 166, 1),
        tri({12, 14}, {11.000000000000002, 13.000000000000002}, {12, 13}, {0.10000000000000001, 0.099999999999999978, 0.10000000000000001}, 167, 1),
        tri({11, 15}, {10, 14.999999999999998}, {10, 14}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 172, 1),
        tri({11, 15}, {10, 14}, {11, 14.000000000000002}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 173, 1),
        tri({12, 15}, {11, 15}, {11, 14.000000000000002}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 174, 1),
        tri({12, 15}, {11, 14.000000000000002}, {12, 14}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 175, 1),
        tri({11, 16}, {10, 15.999999999999998}, {10, 14.999999999999998}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 180, 1),
        tri({11, 16}, {10, 14.999999999999998}, {11, 15}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 181, 1),
        tri({13.318181818181817, 14.954545454545453}, {13.318181818181818, 16.954545454545453}, {11.984848484848483, 14.954545454545455}, {0.24999999999999994, 0.25, 0.25000000000000006}, 191, 1),
        tri({11.984848484848484, 14.954545454545455}, {13.318181818181818, 16.954545454545453}, {13.318181818181818, 22.954545454545457}, {0.25, 0.25, 0.25}, 192, 1),
        tri({11.984848484848484, 14.954545454545455}, {13.318181818181818, 22.954545454545457}, {9.3181818181818166, 22.954545454545457}, {0.25, 0.25, 0.25}, 193, 1),
        tri({11.984848484848484, 14.954545454545455}, {9.3181818181818166, 22.954545454545457}, {9.3181818181818166, 14.954545454545455}, {0.25, 0.25, 0.25}, 194, 1),
    }, 11, 14);
}

// A street scene's re-clip (configs/bench/many/street.yaml at 160x90, render.audit): three triangles of
// a car's mesh (frame 0) fanning about one vertex, and the same surface from frame 1 offset by 3e-7 px.
// A mixed piece became a needle 0.23 px long whose blunt end, a cluster of three vertices within 3.4e-7
// px, rounding had dented; both of its short edges were skipped as non-supporting, which left the
// needle's two nearly parallel sides as its only bounds there, so the next triangle found a 0.16 px
// strip "inside" it and kept it twice (overlap 5.6e-8 px^2). The chord across the cluster bounds it now.
TEST(FragmentAudit, SliverWithADentedEndRegression) {
    expectCleanPixel({
        tri({119.45689520481525, 39.002227384160179}, {119.61341845564452, 38.998984467008441}, {119.61341776961962, 39.001739703343766}, {0.053069473143365513, 0.053069932760962751, 0.053069865823916151}, 671, 0),
        tri({119.61341717946503, 39.004109902005823}, {119.61341776961962, 39.001739703343766}, {120.50524515818346, 38.998961017027867}, {0.053069808241161358, 0.053069865823916151, 0.053072103221894221}, 684, 0),
        tri({119.61341776961962, 39.001739703343766}, {119.61341845564452, 38.998984467008441}, {120.50524515818346, 38.998961017027867}, {0.053069865823916151, 0.053069932760962751, 0.053072103221894221}, 687, 0),
        tri({119.45730497344171, 39.004113383145828}, {119.45689512504578, 39.002227017013624}, {119.83924897898824, 39.00103576949288}, {0.053069428322137235, 0.053069473152090853, 0.053070432391998254}, 3239, 1),
    }, 119, 39);
}

// A wall seen at both frames (all 1/z 0.1, frames coincide and mix): a mixed piece and its unmixed
// remnant both kept the same 0.0047 px^2 triangle.
TEST(FragmentAudit, CoincidentWallRegression) {
    expectCleanPixel({
        tri({6.9210400071494789, 26.780791499017099}, {11.539048744419624, 26.898300211013151}, {11.533699835136154, 27.007250277509449}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 1, 0),
        tri({11.860550034625039, 27.023297005359861}, {11.756948877412214, 26.908998029580093}, {16.696458904887781, 27.151503535922853}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 31, 0),
        tri({11.860550034625039, 27.023297005359861}, {16.696458904887781, 27.151503535922853}, {16.691109995604315, 27.260453602419148}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 32, 0),
        tri({11.751599968128748, 27.017948096076388}, {11.756948877412214, 26.908998029580093}, {11.860550034625042, 27.023297005359858}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 33, 0),
        tri({11.533699835136154, 27.007250277509449}, {11.539048744419624, 26.898300211013151}, {11.756948877412214, 26.908998029580093}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 34, 0),
        tri({11.533699835136154, 27.007250277509449}, {11.756948877412214, 26.908998029580093}, {11.751599968128748, 27.017948096076388}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 35, 0),
        tri({16.696458904887781, 27.151503535922853}, {11.999454383754976, 21.969488002104526}, {16.938964411230543, 22.211993508447286}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 37, 0),
        tri({16.696458904887781, 27.151503535922853}, {11.756948877412214, 26.908998029580093}, {11.999454383754976, 21.969488002104526}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 38, 0),
        tri({11.307241056643807, 31.619910105496132}, {6.9210400071494789, 26.780791499017099}, {11.533699835136154, 27.007250277509449}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 59, 0),
        tri({11.296543238076861, 31.837810238488721}, {6.5749333435938908, 31.606002550712901}, {6.8120899406531841, 26.775442589733629}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 60, 0),
        tri({11.296543238076861, 31.837810238488721}, {6.8120899406531841, 26.775442589733629}, {6.9210400071494789, 26.780791499017099}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 61, 0),
        tri({11.296543238076861, 31.837810238488721}, {6.9210400071494789, 26.780791499017099}, {11.307241056643811, 31.619910105496125}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 62, 0),
        tri({16.453953398545021, 32.09101356339842}, {11.860550034625039, 27.023297005359861}, {16.691109995604315, 27.260453602419148}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 77, 0),
        tri({16.453953398545021, 32.09101356339842}, {11.514443371069458, 31.84850805705566}, {11.751599968128748, 27.017948096076388}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 78, 0),
        tri({16.453953398545021, 32.09101356339842}, {11.751599968128748, 27.017948096076388}, {11.860550034625042, 27.023297005359858}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 79, 0),
        tri({11.514443371069458, 31.84850805705566}, {11.307241056643807, 31.619910105496132}, {11.533699835136154, 27.007250277509449}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 80, 0),
        tri({11.514443371069458, 31.84850805705566}, {11.533699835136154, 27.007250277509449}, {11.751599968128748, 27.017948096076388}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 81, 0),
        tri({12.465236375443659, 27.690423042201338}, {11.756948877412214, 26.908998029580093}, {12.427319507205922, 26.941909911145505}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 84, 1),
        tri({11.652152065023543, 29.043567728421024}, {11.756948877412214, 26.908998029580093}, {12.465236375443659, 27.690423042201338}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 85, 1),
        tri({11.652152065023543, 29.043567728421024}, {12.465236375443659, 27.690423042201338}, {12.531525090724752, 28.99902198865518}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 86, 1),
        tri({9.0896873395416833, 29.173372581975002}, {6.8174388499366501, 26.666492523237331}, {11.756948877412214, 26.908998029580093}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 87, 1),
        tri({9.0896873395416833, 29.173372581975002}, {11.756948877412214, 26.908998029580093}, {11.65215206502355, 29.043567728421024}, {0.10000000000000001, 0.10000000000000001, 0.10000000000000001}, 88, 1),
    }, 11, 27);
}

}  // namespace clipblur
