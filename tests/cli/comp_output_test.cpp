#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

#include "io/image_writer.h"
#include "support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

namespace {

// Camera at (0, 0, -1) looking along +z, 90 degree vfov on an 8 x 8 film: 4 px per world unit in the
// plane z = 0, image right is world -x. Unlit (ambient 1, no lights), so a surface shows its colour.
const char* kCamera = R"(version: 1
film: {width: 8, height: 8, background: [0.2, 0.4, 0.6]}
camera:
  vfov: 90
  keys: [{time: 0, position: [0, 0, -1], view: [0, 0, 1], up: [0, 1, 0]}]
ambient: 1
materials: [{name: paint, color: [0.6, 0.2, 0.0]}]
)";

// A 2 x 4 quad facing the camera spanning world x in [-0.125, 1.875]: raster x from -3.5 to 4.5, so
// columns 0-3 are covered, column 4 exactly half, 5-7 not at all.
const char* kHalfPixel = R"(objects:
  - name: card
    primitive: {type: quad, size: [2, 4]}
    transform: [{time: 0, translate: [0.875, 0, 0], rotate: {axis: [1, 0, 0], angle_deg: -90}}]
render: {method: clipped}
output: {half: false, png_preview: true}
)";

// A 6 x 6 quad covering the film all shutter, moving 1 unit right (world -x) and 0.5 up per frame:
// 4 px/frame right and 2 px/frame up, seen over a half-frame shutter.
const char* kMoving = R"(shutter: {open: 0, close: 0.5}
objects:
  - name: card
    primitive: {type: quad, size: 6}
    transform:
      - {time: 0, translate: [0, 0, 0], rotate: {axis: [1, 0, 0], angle_deg: -90}}
      - {time: 1, translate: [-1, 0.5, 0], rotate: {axis: [1, 0, 0], angle_deg: -90}}
render: {method: clipped, time_integration: sweep}
output: {half: true, aovs: [depth, motion]}
)";

// Writes the job, renders it with `extra` arguments to dir/<stem>.exr; returns the exit code.
int render(const fs::path& dir, const std::string& stem, const std::string& job, const std::string& extra) {
    const fs::path file = dir / (stem + ".yaml");
    std::ofstream(file) << job;
    return testing::runShell(std::string(CLIPBLUR_BINARY) + " render " + file.string() + " --progress none --out " +
               (dir / (stem + ".exr")).string() + " " + extra + " > " + (dir / (stem + ".log")).string() + " 2>&1");
}

using testing::ExrPixels;
using testing::readExrPixels;

}  // namespace

// Premultiplied beauty: the half-covered pixel stores half the surface colour with A = 0.5, and an
// "over" of the film background gives 0.5 (0.6, 0.2, 0) + 0.5 (0.2, 0.4, 0.6) = (0.4, 0.3, 0.3). With
// output.background: bake the file holds that over, opaque. The clipped method's coverage is exact, so
// the only error is float storage (1e-6 is about 30 ulps at 0.4).
TEST(CompOutput, BeautyIsPremultipliedAndBakingIsAnOver) {
    const fs::path dir = testing::freshTempDir("clipblur_comp_premultiplied");
    const std::string job = std::string(kCamera) + kHalfPixel;
    ASSERT_EQ(render(dir, "separate", job, ""), 0);
    ASSERT_EQ(render(dir, "bake", job, "--set output.background=bake"), 0);
    const ExrPixels separate = readExrPixels(dir / "separate.exr");
    const ExrPixels bake = readExrPixels(dir / "bake.exr");
    const float bg[3] = {0.2f, 0.4f, 0.6f};
    const float paint[3] = {0.6f, 0.2f, 0.0f};
    const char* rgb[3] = {"R", "G", "B"};
    for (int y = 0; y < 8; ++y) {
        EXPECT_NEAR(separate.at("A", 2, y), 1.0f, 1e-6f);
        EXPECT_NEAR(separate.at("A", 4, y), 0.5f, 1e-6f);
        EXPECT_EQ(separate.at("A", 6, y), 0.0f);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(separate.at(rgb[c], 2, y), paint[c], 1e-6f);
            EXPECT_NEAR(separate.at(rgb[c], 4, y), 0.5f * paint[c], 1e-6f);
            EXPECT_EQ(separate.at(rgb[c], 6, y), 0.0f);  // no background in the colour
            const float over = separate.at(rgb[c], 4, y) + (1.0f - separate.at("A", 4, y)) * bg[c];
            EXPECT_NEAR(over, 0.5f * paint[c] + 0.5f * bg[c], 1e-6f);
            EXPECT_NEAR(bake.at(rgb[c], 4, y), 0.5f * paint[c] + 0.5f * bg[c], 1e-6f);
            EXPECT_NEAR(bake.at(rgb[c], 6, y), bg[c], 1e-6f);
        }
        EXPECT_EQ(bake.at("A", 4, y), 1.0f);
        EXPECT_EQ(bake.at("A", 6, y), 1.0f);
    }
    // Both previews show the over, once: baking must not put the background in twice.
    for (const char* stem : {"separate", "bake"}) {
        auto in = OIIO::ImageInput::open((dir / (std::string(stem) + ".png")).string());
        ASSERT_TRUE(in) << stem;
        std::vector<std::uint8_t> png(8 * 8 * 3);
        ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, png.data()));
        const std::size_t at = (3 * 8 + 4) * 3;
        EXPECT_EQ(png[at + 0], encodeSrgb8(0.4f)) << stem;
        EXPECT_EQ(png[at + 1], encodeSrgb8(0.3f)) << stem;
        EXPECT_EQ(png[at + 2], encodeSrgb8(0.3f)) << stem;
    }
}

// forward.u / forward.v against the analytic image velocity, Z and motion float beside a half beauty,
// the same bits on 1 and 2 threads, and the header and stats of the frame.
TEST(CompOutput, ForwardVectorsHeaderAndStats) {
    const fs::path dir = testing::freshTempDir("clipblur_comp_motion");
    const std::string job = std::string(kCamera) + kMoving;
    ASSERT_EQ(render(dir, "one", job, "--threads 1"), 0);
    ASSERT_EQ(render(dir, "two", job, "--threads 2"), 0);
    const ExrPixels one = readExrPixels(dir / "one.exr");
    const ExrPixels two = readExrPixels(dir / "two.exr");
    EXPECT_EQ(one.spec.channelformat(one.spec.channelindex("R")), OIIO::TypeDesc::HALF);
    for (const char* name : {"Z", "forward.u", "forward.v"})
        EXPECT_EQ(one.spec.channelformat(one.spec.channelindex(name)), OIIO::TypeDesc::FLOAT) << name;
    EXPECT_EQ(one.spec.channelindex("motion.x"), -1);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            EXPECT_NEAR(one.at("forward.u", x, y), 4.0f, 1e-4f) << x << " " << y;
            EXPECT_NEAR(one.at("forward.v", x, y), 2.0f, 1e-4f) << x << " " << y;
        }
    ASSERT_EQ(one.pixels.size(), two.pixels.size());
    for (std::size_t i = 0; i < one.pixels.size(); ++i) ASSERT_EQ(one.pixels[i], two.pixels[i]) << i;

    // worldToCamera of this camera by hand (Imath row vectors): right = -x, up = y, view = z, and the
    // camera at z = -1 puts world z = 0 at camera z = 1.
    const OIIO::ParamValue* w2c = one.spec.find_attribute("worldToCamera");
    ASSERT_TRUE(w2c);
    const float expected[16] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1};
    for (int i = 0; i < 16; ++i) EXPECT_EQ(static_cast<const float*>(w2c->data())[i], expected[i]) << i;
    EXPECT_EQ(one.spec.get_int_attribute("clipblur:frame", -1), 0);
    EXPECT_FLOAT_EQ(one.spec.get_float_attribute("clipblur:shutterClose"), 0.5f);

    std::ifstream stats(dir / "one.stats.json");
    const nlohmann::json j = nlohmann::json::parse(stats);
    EXPECT_EQ(j.at("counts").at("threads"), 1);
    EXPECT_EQ(j.at("threads"), 1);
    EXPECT_EQ(j.at("config_hash").get<std::string>(), one.spec.get_string_attribute("clipblur:configHash"));
    EXPECT_EQ(j.at("start_time").get<std::string>().size(), std::string("2026-11-25T01:17:28Z").size());
}

// OpenEXR's own reader (exrheader, Debian openexr) sees the channels with their types and the header
// attributes a compositor looks for, independently of OpenImageIO which wrote them.
TEST(CompOutput, ExrheaderReadsChannelsTypesAndMetadata) {
    const fs::path dir = testing::freshTempDir("clipblur_comp_exrheader");
    const std::string job = std::string(kCamera) + kMoving;
    ASSERT_EQ(render(dir, "frame", job,
                     "--set output.compression=piz --set frames.fps=23.976023976023978 "
                     "--set 'output.cryptomatte={name: CryptoObject, depth: 2}'"),
              0);
    const fs::path listing = dir / "exrheader.txt";
    ASSERT_EQ(testing::runShell("exrheader " + (dir / "frame.exr").string() + " > " + listing.string() + " 2>&1"), 0)
        << "exrheader (Debian openexr, scripts/setup.sh) must be installed";
    std::ifstream in(listing);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const char* expected[] = {
        "    A, 16-bit floating-point, sampling 1 1\n",
        "    B, 16-bit floating-point, sampling 1 1\n",
        "    CryptoObject00.A, 32-bit floating-point, sampling 1 1\n",
        "    CryptoObject00.R, 32-bit floating-point, sampling 1 1\n",
        "    G, 16-bit floating-point, sampling 1 1\n",
        "    R, 16-bit floating-point, sampling 1 1\n",
        "    Z, 32-bit floating-point, sampling 1 1\n",
        "    forward.u, 32-bit floating-point, sampling 1 1\n",
        "    forward.v, 32-bit floating-point, sampling 1 1\n",
        "compression (type compression): piz\n",
        "framesPerSecond (type rational): 24000/1001",
        "chromaticities (type chromaticities):\n    red   (0.64 0.33)\n    green (0.3 0.6)\n    blue  (0.15 0.06)\n"
        "    white (0.3127 0.329)\n",
        "worldToCamera (type m44f):\n",
        "worldToNDC (type m44f):\n",
        "expTime (type float): 0.0208542\n",  // half a frame at 24000/1001 fps
        "clipblur:frame (type int): 0\n",
        "clipblur:shutterClose (type float): 0.5\n",
        "clipblur:configHash (type string): \"",
        "cryptomatte/3ae39a5/name (type string): \"CryptoObject\"\n",
        "cryptomatte/3ae39a5/hash (type string): \"MurmurHash3_32\"\n",
        "cryptomatte/3ae39a5/conversion (type string): \"uint32_to_float32\"\n",
        "cryptomatte/3ae39a5/manifest (type string): \"{\"card\":\"",
    };
    for (const char* line : expected) EXPECT_NE(text.find(line), std::string::npos) << line << "\nin:\n" << text;
    EXPECT_EQ(text.find("motion.x"), std::string::npos);
    EXPECT_EQ(text.find("CryptoObject01"), std::string::npos);  // depth 2: one layer
    EXPECT_NE(text.find("Software (type string): \"clipblur "), std::string::npos);
}

}  // namespace clipblur
