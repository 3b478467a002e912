#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

#include "support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

namespace {

// Four objects, each with its own untextured material: a ball moving across a turning box, a floor and a
// wall far behind (still: with sweep integration the tiles where only the ball passes in front of it
// composite it as a still backdrop); blurred edges where several objects share a pixel. The render
// settings come from the test case.
const char* kScene = R"(version: 1
film: {width: 40, height: 24, background: 0.3}
camera:
  vfov: 40
  keys: [{time: 0, position: [0, 1, -8], view: [0, -0.1, 1], up: [0, 1, 0]}]
materials:
  - {name: m_ball, color: [0.9, 0.3, 0.2]}
  - {name: m_box, color: [0.2, 0.7, 0.3]}
  - {name: m_floor, color: 0.5}
  - {name: m_wall, color: 0.4}
lights: [{type: directional, direction: [0.3, -1, 0.5]}]
objects:
  - name: ball
    material: m_ball
    primitive: {type: sphere, size: 1.5, segments: 24}
    transform: [{time: 0, translate: [-2.5, 0.8, 0]}, {time: 1, translate: [2.5, 0.8, 0.5]}]
  - name: box
    material: m_box
    primitive: {type: box, size: 1.2}
    transform:
      - {time: 0, translate: [0.5, 0.6, 1.5], rotate: {axis: [0, 1, 0], angle_deg: 0}}
      - {time: 1, translate: [0.5, 0.6, 1.5], rotate: {axis: [0, 1, 0], angle_deg: 60}}
  - name: floor
    material: m_floor
    primitive: {type: quad, size: 12}
  - name: wall
    material: m_wall
    primitive: {type: quad, size: 12}
    transform: [{time: 0, translate: [0, 3, 6], rotate: {axis: [1, 0, 0], angle_deg: -90}}]
output: {half: false, cryptomatte: {name: CryptoObject}}
)";

using testing::ExrPixels;

// A decoder written from the Cryptomatte specification alone: find the type whose
// cryptomatte/<key>/name is `type`, read the object's ID from the manifest (hex of the float's bits),
// and sum, over the layers <type>00, <type>01, ..., the coverage (G, A) of every rank whose ID (R, B)
// has exactly those bits.
std::vector<float> decodeMatte(const ExrPixels& e, const std::string& type, const std::string& object) {
    std::string manifest;
    for (const OIIO::ParamValue& p : e.spec.extra_attribs) {
        const std::string name = p.name().string();
        if (name.rfind("cryptomatte/", 0) == 0 && name.size() > 5 && name.substr(name.size() - 5) == "/name" &&
            e.spec.get_string_attribute(name) == type)
            manifest = e.spec.get_string_attribute(name.substr(0, name.size() - 5) + "/manifest");
    }
    EXPECT_FALSE(manifest.empty()) << "no manifest for " << type;
    const std::uint32_t bits = static_cast<std::uint32_t>(std::stoul(nlohmann::json::parse(manifest).at(object).get<std::string>(), nullptr, 16));
    std::vector<float> matte(static_cast<std::size_t>(e.spec.width) * e.spec.height, 0.0f);
    for (int layer = 0;; ++layer) {
        const std::string prefix = type + (layer < 10 ? "0" : "") + std::to_string(layer) + ".";
        const int r = e.spec.channelindex(prefix + "R");
        if (r < 0) break;
        const int pairs[2][2] = {{r, e.spec.channelindex(prefix + "G")},
                                 {e.spec.channelindex(prefix + "B"), e.spec.channelindex(prefix + "A")}};
        for (std::size_t i = 0; i < matte.size(); ++i)
            for (const auto& pair : pairs) {
                const float id = e.at(pair[0], i);
                std::uint32_t id_bits;
                std::memcpy(&id_bits, &id, 4);
                if (id_bits == bits) matte[i] += e.at(pair[1], i);
            }
    }
    return matte;
}

}  // namespace

struct MatteCase {
    const char* name;
    const char* render;  // the job's render section
    const char* object;  // whose matte is checked (its material is materials.<material>)
    int material;
};

class CryptomatteRender : public ::testing::TestWithParam<MatteCase> {};

// The matte of one object, decoded from the file as the specification says, equals a render of the
// same scene in which that object is white and everything else black, unlit (ambient 1, no lights):
// there each pixel's R is the object's share of pixel area x shutter time, accumulated as colour is.
// Stochastic: both are (samples on the object) / samples, rounded to float once. Clipped methods: the
// same fragments, mix factors and weights make both; 1e-6 allows for the sums' rounding.
TEST_P(CryptomatteRender, DecodedMatteEqualsAWhiteOnBlackRender) {
    const MatteCase& c = GetParam();
    const fs::path dir = testing::freshTempDir(std::string("clipblur_cryptomatte_render_") + c.name);
    std::ofstream(dir / "scene.yaml") << kScene << "render: " << c.render << "\n";
    const std::string render = std::string(CLIPBLUR_BINARY) + " render " + (dir / "scene.yaml").string() + " --progress none";
    const std::string quiet = " > " + (dir / "log.txt").string() + " 2>&1";
    ASSERT_EQ(testing::runShell(render + " --threads 1 --out " + (dir / "crypto.exr").string() + quiet), 0);
    ASSERT_EQ(testing::runShell(render + " --threads 2 --out " + (dir / "crypto2.exr").string() + quiet), 0);
    std::string colours;
    for (int m = 0; m < 4; ++m)
        colours += " --set materials." + std::to_string(m) + ".color=" + (m == c.material ? "1" : "0");
    ASSERT_EQ(testing::runShell(render + colours + " --set ambient=1 --set 'lights=[]' --out " +
                                (dir / "white.exr").string() + quiet),
              0);
    const ExrPixels crypto = testing::readExrPixels(dir / "crypto.exr");
    const ExrPixels crypto2 = testing::readExrPixels(dir / "crypto2.exr");
    const ExrPixels white = testing::readExrPixels(dir / "white.exr");
    ASSERT_EQ(crypto.pixels, crypto2.pixels);  // bit for bit on 1 and 2 threads

    const std::vector<float> matte = decodeMatte(crypto, "CryptoObject", c.object);
    const int r = white.spec.channelindex("R");
    int partial = 0;
    for (std::size_t i = 0; i < matte.size(); ++i) {
        EXPECT_NEAR(matte[i], white.at(r, i), 1e-6f) << i;
        if (matte[i] > 0.0f && matte[i] < 1.0f) ++partial;
    }
    EXPECT_GT(partial, 10);  // the object's blurred edges are in the test

    // Every pixel's coverages sum to its alpha: four objects fit in depth 6.
    const int alpha = crypto.spec.channelindex("A");
    std::vector<float> sum(matte.size(), 0.0f);
    for (const char* object : {"ball", "box", "floor", "wall"}) {
        const std::vector<float> m = decodeMatte(crypto, "CryptoObject", object);
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += m[i];
    }
    for (std::size_t i = 0; i < sum.size(); ++i) EXPECT_NEAR(sum[i], crypto.at(alpha, i), 1e-6f) << i;
}

// The turning box under the stochastic renderer; the translating ball under every clipped method:
// point subframes (re-clips), sweep (swept fragments), accumulation and the frame-0 ablation (no blur:
// only its edges are partial); the box under subframes (its turn splits the shutter into segments);
// under sweep the wall, much of it a still backdrop (8 px tiles, so some tiles hold no floor). A fixed
// subframe count keeps the renders short; the mattes follow the colour whatever the count.
INSTANTIATE_TEST_SUITE_P(
    Methods, CryptomatteRender,
    ::testing::Values(MatteCase{"Stochastic", "{method: stochastic, samples: 16, seed: 5}", "box", 1},
                      MatteCase{"Clipped", "{method: clipped, subframes: 16, tile_size: 8}", "ball", 0},
                      MatteCase{"ClippedBox", "{method: clipped, subframes: 16, tile_size: 8}", "box", 1},
                      MatteCase{"Sweep", "{method: clipped, time_integration: sweep, subframes: 16, tile_size: 8}", "ball", 0},
                      MatteCase{"SweepBackdrop", "{method: clipped, time_integration: sweep, subframes: 16, tile_size: 8}",
                                "wall", 3},
                      MatteCase{"Accumulation", "{method: accumulation, samples: 8}", "ball", 0},
                      MatteCase{"Frame0Only", "{method: frame0_only}", "ball", 0}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace clipblur
