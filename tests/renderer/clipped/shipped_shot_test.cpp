#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/job_loader.h"
#include "renderer/clipped/error_target.h"
#include "renderer/render.h"
#include "scene/pixel_bounds.h"
#include "support/cli_harness.h"
#include "support/render_compare.h"

namespace clipblur {

namespace {

using testing::meanSquaredDifference;

namespace fs = std::filesystem;

const fs::path kShot = fs::path(CLIPBLUR_SOURCE_DIR) / "configs" / "shot.yaml";
// The same shot without image textures and normals (configs/shot/street_plain.gltf).
const fs::path kPlainShot = fs::path(CLIPBLUR_SOURCE_DIR) / "configs" / "bench" / "shot_plain.yaml";
// Ambient light only: the clipped method mixes a surface's lighting between the frames rather than
// per time (docs/design.md, "Shading"), and the wheels turn under the sun.
const std::vector<std::string> kAmbientOnly = {"lights=[]", "ambient=1"};
constexpr int kFrame = 24;  // the shipped job's frame
constexpr int kSamples = 400;

int objectNamed(const RenderJob& job, const std::string& name) {
    for (std::size_t i = 0; i < job.scene.objects.size(); ++i)
        if (job.scene.objects[i].name == name) return static_cast<int>(i);
    ADD_FAILURE() << "no object " << name;
    return -1;
}

// The pixels (row-major over the render window) where any of `objects` covers some of the pixel.
std::vector<bool> coveredBy(const RenderResult& r, const std::vector<int>& objects) {
    std::vector<bool> mask(r.objects.pixels.size(), false);
    for (std::size_t p = 0; p < mask.size(); ++p)
        for (const ObjectShare& s : r.objects.pixels[p])
            for (const int o : objects) mask[p] = mask[p] || (s.object == o && s.coverage > 0.0);
    return mask;
}

// Two stochastic renders with independent seeds and the statistic of
// tests/renderer/clipped/gltf_motion_vs_stochastic_test.cpp: V = msd(s1, s2) / 4 estimates the variance
// of their average, which an exact render differs from by V in the mean.
struct StochasticPair {
    RenderResult s1, s2;
    double variance(const std::vector<bool>& mask) const { return meanSquaredDifference(s1, s2, nullptr, mask) / 4.0; }
    double ratio(const RenderResult& r, const std::vector<bool>& mask) const {
        return meanSquaredDifference(r, s1, &s2, mask) / variance(mask);
    }
};

StochasticPair stochasticPair(const std::function<RenderJob(std::vector<std::string>)>& load,
                              const std::function<void(RenderJob&)>& adjust) {
    StochasticPair pair;
    for (const int seed : {1, 2}) {
        RenderJob job = load({"render.method=stochastic", "render.samples=" + std::to_string(kSamples),
                              "render.seed=" + std::to_string(seed)});
        adjust(job);
        (seed == 1 ? pair.s1 : pair.s2) = renderFrame(job, kFrame);
    }
    return pair;
}

// Coverage-weighted mean x (pixels) of `object` in a render.
double centroidX(const RenderResult& r, int object, int width) {
    double sum = 0.0, weight = 0.0;
    for (std::size_t p = 0; p < r.objects.pixels.size(); ++p)
        for (const ObjectShare& s : r.objects.pixels[p])
            if (s.object == object) {
                sum += s.coverage * (double(p % std::size_t(width)) + 0.5);
                weight += s.coverage;
            }
    return sum / weight;
}

// The shot's glTF with every wheel held at the pose its spin has at `seconds` (a key time of the spin)
// instead of spinning (the cars still drive), in a fresh folder beside a copy of the job.
fs::path heldWheelsCopy(double seconds) {
    const fs::path dir = testing::freshTempDir("clipblur_shot_held_wheels");
    fs::copy(kShot.parent_path() / "shot", dir / "shot", fs::copy_options::recursive);
    fs::copy_file(kShot, dir / "shot.yaml");
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(dir / "shot" / "street.gltf"));
    std::ifstream bin(dir / "shot" / "street.bin", std::ios::binary);
    const auto floats = [&](int accessor, std::size_t first, std::size_t count) {
        const nlohmann::json& a = gltf["accessors"][accessor];
        const nlohmann::json& v = gltf["bufferViews"][a["bufferView"].get<int>()];
        std::vector<float> out(count);
        bin.seekg(std::streamoff(v["byteOffset"].get<std::size_t>() + 4 * first));
        bin.read(reinterpret_cast<char*>(out.data()), std::streamsize(4 * count));
        return out;
    };
    nlohmann::json& animation = gltf["animations"][0];
    nlohmann::json kept = nlohmann::json::array();
    for (const auto& channel : animation["channels"]) {
        nlohmann::json& node = gltf["nodes"][channel["target"]["node"].get<int>()];
        if (node["name"].get<std::string>().find("_wheel_") == std::string::npos) {
            kept.push_back(channel);
            continue;
        }
        const nlohmann::json& sampler = animation["samplers"][channel["sampler"].get<int>()];
        const int input = sampler["input"];
        const std::vector<float> times = floats(input, 0, gltf["accessors"][input]["count"]);
        const auto key = std::size_t(std::find(times.begin(), times.end(), float(seconds)) - times.begin());
        EXPECT_LT(key, times.size()) << "no spin key at " << seconds << " s";
        const std::vector<float> q = floats(sampler["output"], 4 * key, 4);
        node["rotation"] = {q[0], q[1], q[2], q[3]};
    }
    EXPECT_EQ(animation["channels"].size() - kept.size(), 12u);  // 3 cars x 4 wheels
    animation["channels"] = kept;
    std::ofstream(dir / "shot" / "street.gltf") << gltf.dump(1);
    return dir / "shot.yaml";
}

}  // namespace

// The shipped job's clipped settings at 128x72 against two 400-sample stochastic renders, on the shot
// without image textures: the clipped method reads a texture once per piece over its footprint where
// the stochastic one integrates the bilinear image, which at this size (a window's 32 texels in about
// 9 pixels) differs by far more than the noise on its own (docs/design.md, "Shading"); the motion is
// what this test is about. Ratio as in GltfRender.MorphSkinAndResampledMotionAgreeWithTheStochasticReference.
// Measured 2.5 here, not the 1.5 that test allows: the excess sits at the spinning wheels (with the
// wheels held still, the right third of the image, the blue car's, gives 0.96), whose rotation the
// stochastic reference follows by Embree time steps allowed 0.1 px of chord error
// (EmbreeScene::kMaxChordErrorPixels). A wheel, car or walker off its path, or a blur left out, is a
// bias over whole edges: the zero-length shutter below is above 20 on the cars' pixels alone.
// Then that the cars move: between frames 23 and 25 a car crosses the image against a still building.
TEST(ShippedShot, ClippedAgreesWithStochasticAndTheCarsMove) {
    const auto load = [](std::vector<std::string> overrides) {
        for (const char* o : {"film.width=128", "film.height=72", "output.cryptomatte={}"}) overrides.push_back(o);
        overrides.insert(overrides.end(), kAmbientOnly.begin(), kAmbientOnly.end());
        return loadJob(kPlainShot, overrides);
    };
    const RenderJob job = load({});
    ASSERT_EQ(job.render.method, Method::Clipped);
    const RenderResult clipped = renderFrame(job, kFrame);
    const StochasticPair pair = stochasticPair(load, [](RenderJob&) {});
    const double ratio = pair.ratio(clipped, {});
    RecordProperty("ratio", std::to_string(ratio));
    EXPECT_LT(ratio, 4.0) << "variance " << pair.variance({});

    const std::vector<int> cars = {objectNamed(job, "car_red"), objectNamed(job, "car_blue"),
                                   objectNamed(job, "car_yellow")};
    const std::vector<bool> car_pixels = coveredBy(clipped, cars);
    const RenderResult still = renderFrame(load({"shutter.open=0", "shutter.close=0"}), kFrame);
    // A car blurs over 2-4 px here: at its edges the blurred and the still frame differ by tens of
    // percent, far above 400-sample noise (a ratio of 1 would mean no motion at all).
    EXPECT_GT(pair.ratio(still, car_pixels), 20.0);

    // Still frames (zero-length shutter) 23 and 25: car_blue drives 0.5 m towards -x in 2/24 s, about
    // 4 px at its 13 m depth and 99 px focal length (36 px / tan(yfov / 2)), while the pan and dolly move
    // a still building by about a pixel. Measured: the car's shift less the building's, -3.5 px;
    // centroids of partly hidden boxes are only near the projection, hence the loose bound. A car that
    // did not drive would give about 0.
    const RenderResult a = renderFrame(load({"shutter.open=0", "shutter.close=0"}), kFrame - 1);
    const RenderResult b = renderFrame(load({"shutter.open=0", "shutter.close=0"}), kFrame + 1);
    const int car = objectNamed(job, "car_blue"), building = objectNamed(job, "building_3");
    const double shift = (centroidX(b, car, 128) - centroidX(a, car, 128)) -
                         (centroidX(b, building, 128) - centroidX(a, building, 128));
    RecordProperty("car_shift_px", std::to_string(shift));
    EXPECT_LT(shift, -2.0);
}

// The red car's front wheel spins 33 degrees in the shutter (its five spokes are the wheel.png texture
// on the cap) while the car drives 0.19 m. In a window around it at the shipped 640x360, over the pixels
// the wheel covers entirely, the clipped render is close to the stochastic pair and far from the same
// shot with every wheel held at its mid-shutter pose (cars still driving): the spin's blur is there.
// Not within noise: the texture is read once per piece over its footprint, where the reference
// integrates the bilinear image (docs/design.md, "Shading"), and the reference follows the turn by time
// steps allowed 0.1 px of chord error. Measured: ratio 12.5 against the pair; the held wheel 714 (a
// 400-sample stochastic render of the held wheel, 662), so the clipped image's deviation from the reference is
// about an eighth (root of 12.5 / 714) of the spin's effect; the bounds leave a factor 2 either way.
TEST(ShippedShot, SpinningWheelBlursAsTheStochasticReferenceDoes) {
    const auto load_from = [](const fs::path& file) {
        return [file](std::vector<std::string> overrides) {
            overrides.push_back("output.cryptomatte={}");
            overrides.insert(overrides.end(), kAmbientOnly.begin(), kAmbientOnly.end());
            return loadJob(file, overrides);
        };
    };
    const auto load = load_from(kShot);
    // Find the wheel at 128x72 (each pixel 5x5 of the full film) and frame it with a margin.
    const RenderJob small = load({"film.width=128", "film.height=72"});
    const int wheel = objectNamed(small, "car_red_wheel_fl");
    const RenderResult found = renderFrame(small, kFrame);
    const std::vector<bool> found_pixels = coveredBy(found, {wheel});
    PixelBounds box = PixelBounds::corners(128, 72, 0, 0);
    for (int y = 0; y < 72; ++y)
        for (int x = 0; x < 128; ++x)
            if (found_pixels[std::size_t(y * 128 + x)])
                box = PixelBounds::corners(std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x + 1),
                                           std::max(box.y1, y + 1));
    ASSERT_FALSE(box.empty());
    const PixelBounds window = PixelBounds::corners(5 * box.x0 - 4, 5 * box.y0 - 4, 5 * box.x1 + 4, 5 * box.y1 + 4)
                                   .intersect(PixelBounds::sized(0, 0, 640, 360));
    RecordProperty("window", toString(window));
    const auto in_window = [&](RenderJob& j) { j.render.window = window; };

    // Held at frame 24's pose (1 s, the middle of its centred shutter): the same wheel without the blur.
    const auto load_held = load_from(heldWheelsCopy(1.0));
    RenderJob spinning = load({}), held = load_held({});
    in_window(spinning);
    in_window(held);
    const RenderResult clipped = renderFrame(spinning, kFrame), clipped_held = renderFrame(held, kFrame);
    const StochasticPair pair = stochasticPair(load, in_window);
    // Pixels the wheel covers entirely at every moment of the shutter, in the held render.
    std::vector<bool> inside(clipped_held.objects.pixels.size(), false);
    for (std::size_t p = 0; p < inside.size(); ++p)
        for (const ObjectShare& share : clipped_held.objects.pixels[p])
            inside[p] = inside[p] || (share.object == wheel && share.coverage > 0.999);
    ASSERT_GT(std::count(inside.begin(), inside.end(), true), 100);
    const double ratio = pair.ratio(clipped, inside), held_ratio = pair.ratio(clipped_held, inside);
    RecordProperty("ratio", std::to_string(ratio));
    RecordProperty("held_ratio", std::to_string(held_ratio));
    EXPECT_LT(ratio, 25.0);
    EXPECT_GT(held_ratio, 350.0);
}

// render.error_target on the plain shot at 160x90 (sweep): the wheels turn 32.6 degrees, one segment
// under auto (60 degrees an object), with every layer kept where they pass. Under the 15-degree rule
// it made 3, whose floor of work (45 re-clips, 7e-4 from the reference from 34 px of spacing up) met
// targets of 1e-2 and 3e-3 at 0.07 and 0.24 of the target until fewerSegments (error_target.cpp) cut
// them. They must be within issue 20's 0.5 .. 1.5 of the target, at one re-clip a moving tile or more,
// and no more work than that floor. Reference: 0.25 px, re-clips following.
TEST(ShippedShot, LooseErrorTargetsAreMetInOneSegment) {
    RenderJob job = loadJob(kPlainShot.string(), {"film.width=160", "film.height=90", "render.time_integration=sweep",
                                                  "render.sweep_spacing=0.25", "render.max_subframes=4096"});
    const RenderResult reference = renderFrame(job, kFrame);
    ASSERT_EQ(reference.stats.clipped().segments, 1);
    job.render.sweep_spacing = 1.0;
    job.render.max_subframes = 256;
    for (const double target : {1e-2, 3e-3}) {
        job.render.error_target = target;
        const RenderResult r = renderFrame(job, kFrame);
        const ClippedStats& stats = r.stats.clipped();
        EXPECT_EQ(stats.segments, 1) << target;
        EXPECT_LT(stats.subframes_total, 45) << target;
        const double error = rmsDifference(reference.image, r.image);
        RecordProperty("error_" + std::to_string(target), std::to_string(error));
        RecordProperty("reclips_" + std::to_string(target), std::to_string(stats.subframes_total));
        EXPECT_GT(error, 0.5 * target) << target;
        EXPECT_LT(error, 1.5 * target) << target;
    }
}

}  // namespace clipblur
