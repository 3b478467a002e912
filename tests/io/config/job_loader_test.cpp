#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/job_loader.h"
#include "scene/obj_loader.h"
#include "tests/io/config/config_test_util.h"

namespace clipblur {

using clipblur::testing::catchError;
using clipblur::testing::testDir;
using clipblur::testing::writeFile;

namespace {

const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
const char* kTriangleObjMoved = "v 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\nf 1 2 3\nf 2 4 3\n";

const char* kYamlJob = R"(version: 1
film: {width: 320, height: 200, background: [0.1, 0.2, 0.3]}
camera:
  focal_length: 50
  film_height: 24
  keys:
    - {time: 0, position: [0, 1, -5], view: [0, 0, 1], up: [0, 1, 0]}
    - {time: 1, position: [0, 1, -6], view: [0, 0.1, 1], up: [0.1, 1, 0]}
shutter: {open: 0.25, close: 0.75}
frames: {first: 3, last: 7, fps: 30}
materials:
  - {name: red, color: [1, 0, 0], two_sided: false}
  - {name: check, color: 0.9, texture: {type: checker, color2: 0.1, scale: 0.5}}
  - {name: lamp, color: 0.2, emission: [2, 1, 0.5]}
  - {name: sign, color: [0, 1, 0], unlit: true}
lights:
  - {type: directional, direction: [0, -1, 0], intensity: 2}
  - {type: point, position: [1, 2, 3], color: [1, 0.5, 0.25]}
ambient: [0.05, 0.05, 0.1]
objects:
  - name: ground
    material: check
    primitive: {type: grid, size: [4, 2], divisions: [4, 2]}
  - name: ball
    material: red
    primitive: {type: sphere, size: 1, segments: 8}
    transform:
      - {time: 0, translate: [0, 1, 0], rotate: {axis: [0, 1, 0], angle_deg: 0}, scale: 1}
      - {time: 1, translate: [1, 1, 0], rotate: {axis: [0, 1, 0], angle_deg: 45}, scale: [1, 2, 1]}
  - name: mesh
    obj: tri.obj
    deformation:
      - {time: 0, obj: tri.obj}
      - {time: 1, obj: tri_moved.obj}
render:
  method: stochastic
  samples: 8
  subframes: 12
  max_subframes: 64
  path_method: rk4
  ode_steps: 5
  time_integration: sweep
  sweep_spacing: 2.5
  reclip_spacing: 0.75
  sweep_time: exact
  visibility_rays: 2
  shadows: true
  seed: 18446744073709551615
  tile_size: 16
output: {path: out.exr, half: false, png_preview: true, aovs: [motion, depth], stats: s.json}
)";

const char* kJsonJob = R"({
  "version": 1,
  "film": {"width": 320, "height": 200, "background": [0.1, 0.2, 0.3]},
  "camera": {
    "focal_length": 50, "film_height": 24,
    "keys": [
      {"time": 0, "position": [0, 1, -5], "view": [0, 0, 1], "up": [0, 1, 0]},
      {"time": 1, "position": [0, 1, -6], "view": [0, 0.1, 1], "up": [0.1, 1, 0]}
    ]
  },
  "shutter": {"open": 0.25, "close": 0.75},
  "frames": {"first": 3, "last": 7, "fps": 30},
  "materials": [
    {"name": "red", "color": [1, 0, 0], "two_sided": false},
    {"name": "check", "color": 0.9, "texture": {"type": "checker", "color2": 0.1, "scale": 0.5}},
    {"name": "lamp", "color": 0.2, "emission": [2, 1, 0.5]},
    {"name": "sign", "color": [0, 1, 0], "unlit": true}
  ],
  "lights": [
    {"type": "directional", "direction": [0, -1, 0], "intensity": 2},
    {"type": "point", "position": [1, 2, 3], "color": [1, 0.5, 0.25]}
  ],
  "ambient": [0.05, 0.05, 0.1],
  "objects": [
    {"name": "ground", "material": "check", "primitive": {"type": "grid", "size": [4, 2], "divisions": [4, 2]}},
    {"name": "ball", "material": "red", "primitive": {"type": "sphere", "size": 1, "segments": 8},
     "transform": [
       {"time": 0, "translate": [0, 1, 0], "rotate": {"axis": [0, 1, 0], "angle_deg": 0}, "scale": 1},
       {"time": 1, "translate": [1, 1, 0], "rotate": {"axis": [0, 1, 0], "angle_deg": 45}, "scale": [1, 2, 1]}
     ]},
    {"name": "mesh", "obj": "tri.obj",
     "deformation": [{"time": 0, "obj": "tri.obj"}, {"time": 1, "obj": "tri_moved.obj"}]}
  ],
  "render": {"method": "stochastic", "samples": 8, "subframes": 12, "max_subframes": 64, "path_method": "rk4",
             "ode_steps": 5, "time_integration": "sweep", "sweep_spacing": 2.5, "reclip_spacing": 0.75, "sweep_time": "exact", "visibility_rays": 2, "shadows": true, "seed": 18446744073709551615, "tile_size": 16},
  "output": {"path": "out.exr", "half": false, "png_preview": true, "aovs": ["motion", "depth"], "stats": "s.json"}
}
)";

// Minimal valid job; `extra` lines are appended at top level.
std::string minimalYaml(const std::string& extra = "") {
    return "version: 1\n"
           "camera:\n"
           "  keys:\n"
           "    - {time: 0, position: [0, 0, -5]}\n"
           "objects:\n"
           "  - primitive: {type: box}\n" +
           extra;
}

void expectVec(const glm::dvec3& a, const glm::dvec3& b) {
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.z, b.z);
}

}  // namespace

TEST(JobLoader, YamlAndJsonGiveTheSameJob) {
    const auto dir = testDir();
    writeFile(dir / "tri.obj", kTriangleObj);
    writeFile(dir / "tri_moved.obj", kTriangleObjMoved);
    const RenderJob y = loadJob(writeFile(dir / "job.yaml", kYamlJob));
    const RenderJob j = loadJob(writeFile(dir / "job.json", kJsonJob));

    for (const RenderJob* job : {&y, &j}) {
        const Scene& s = job->scene;
        EXPECT_EQ(s.film.width, 320);
        EXPECT_EQ(s.film.height, 200);
        expectVec(s.film.background, {0.1, 0.2, 0.3});
        // vfov = 2 atan(24 / (2 * 50)) in degrees.
        EXPECT_NEAR(s.camera.vfov_degrees, 2.0 * std::atan(0.24) * 180.0 / M_PI, 1e-12);
        ASSERT_EQ(s.camera.keys.size(), 2u);
        expectVec(s.camera.keys[1].position, {0, 1, -6});
        expectVec(s.camera.keys[1].up, {0.1, 1, 0});
        EXPECT_EQ(job->shutter.open, 0.25);
        EXPECT_EQ(job->shutter.close, 0.75);
        EXPECT_EQ(job->frames.first, 3);
        EXPECT_EQ(job->frames.last, 7);
        EXPECT_EQ(job->frames.fps, 30.0);
        ASSERT_EQ(s.materials.size(), 4u);
        EXPECT_FALSE(s.materials[0].two_sided);
        EXPECT_EQ(s.materials[0].model, ShadingModel::Lit);  // the defaults: lit, no emission
        expectVec(s.materials[0].emission, glm::dvec3(0.0));
        EXPECT_EQ(s.materials[1].texture.kind, Texture::Kind::Checker);
        EXPECT_EQ(s.materials[1].texture.scale, 0.5);
        expectVec(s.materials[1].base_color, glm::dvec3(0.9));
        expectVec(s.materials[2].emission, {2, 1, 0.5});
        EXPECT_EQ(s.materials[2].model, ShadingModel::Lit);
        EXPECT_EQ(s.materials[3].model, ShadingModel::Unlit);
        expectVec(s.materials[3].base_color, {0, 1, 0});
        ASSERT_EQ(s.lights.size(), 2u);
        EXPECT_EQ(s.lights[0].kind, Light::Kind::Directional);
        EXPECT_EQ(s.lights[0].intensity, 2.0);
        EXPECT_EQ(s.lights[1].kind, Light::Kind::Point);
        expectVec(s.lights[1].position, {1, 2, 3});
        expectVec(s.ambient, {0.05, 0.05, 0.1});
        ASSERT_EQ(s.objects.size(), 3u);
        EXPECT_EQ(s.objects[0].material, 1);
        EXPECT_EQ(s.objects[0].mesh.triangles.size(), 16u);  // 4 x 2 cells, 2 triangles each
        EXPECT_EQ(s.objects[1].material, 0);
        ASSERT_EQ(s.objects[1].transform.size(), 2u);
        // 45 degrees about y: w = cos(22.5 deg), y = sin(22.5 deg).
        EXPECT_NEAR(s.objects[1].transform[1].rotate.w, std::cos(M_PI / 8), 1e-15);
        EXPECT_NEAR(s.objects[1].transform[1].rotate.y, std::sin(M_PI / 8), 1e-15);
        expectVec(s.objects[1].transform[1].scale, {1, 2, 1});
        EXPECT_EQ(s.objects[2].mesh.triangles.size(), 2u);
        ASSERT_EQ(s.objects[2].deformation.size(), 2u);
        expectVec(s.objects[2].deformation[1].positions[3], {1, 1, 1});
        EXPECT_EQ(job->render.method, Method::Stochastic);
        EXPECT_EQ(job->render.samples, 8);
        EXPECT_EQ(job->render.subframes, 12);
        EXPECT_EQ(job->render.max_subframes, 64);
        EXPECT_EQ(job->render.path_method, PathMethod::RK4);
        EXPECT_EQ(job->render.ode_steps, 5);
        EXPECT_EQ(job->render.time_integration, TimeIntegration::Sweep);
        EXPECT_EQ(job->render.sweep_spacing, 2.5);
        EXPECT_EQ(job->render.reclip_spacing, 0.75);
        EXPECT_EQ(job->render.sweep_time, SweepTime::Exact);
        EXPECT_EQ(job->render.visibility_rays, 2);
        EXPECT_TRUE(job->render.shadows);
        EXPECT_EQ(job->render.seed, 18446744073709551615ull);
        EXPECT_EQ(job->render.tile_size, 16);
        EXPECT_EQ(job->output.path, "out.exr");
        EXPECT_FALSE(job->output.half);
        EXPECT_TRUE(job->output.png_preview);
        EXPECT_TRUE(job->output.aov_depth);
        EXPECT_FALSE(job->output.aov_coverage);
        EXPECT_TRUE(job->output.aov_motion);
        EXPECT_EQ(job->output.stats_path, "s.json");
    }
    EXPECT_EQ(y.scene.objects[1].mesh.positions, j.scene.objects[1].mesh.positions);
    EXPECT_EQ(y.config_hash, j.config_hash);
}

TEST(JobLoader, OutputCompressionBackgroundAndCryptomatte) {
    const RenderJob job = loadJobFromText(
        minimalYaml("render: {method: stochastic}\n"
                    "output: {compression: piz, background: bake, cryptomatte: {name: CryptoAsset, depth: 4}}\n"),
        "c.yaml");
    EXPECT_EQ(job.output.compression, ExrCompression::Piz);
    EXPECT_EQ(job.output.background, BackgroundMode::Bake);
    EXPECT_TRUE(job.output.cryptomatte.enabled);
    EXPECT_EQ(job.output.cryptomatte.name, "CryptoAsset");
    EXPECT_EQ(job.output.cryptomatte.depth, 4);
    const RenderJob plain = loadJobFromText(minimalYaml(), "p.yaml");
    EXPECT_EQ(plain.output.compression, ExrCompression::Zip);
    EXPECT_EQ(plain.output.background, BackgroundMode::Separate);
    EXPECT_FALSE(plain.output.cryptomatte.enabled);
    // Every method writes ID mattes (the clipped ones from their fragments' objects).
    for (const char* method : {"clipped", "accumulation", "frame0_only"}) {
        const RenderJob clipped = loadJobFromText(
            minimalYaml(std::string("render: {method: ") + method + "}\noutput: {cryptomatte: {}}\n"), "m.yaml");
        EXPECT_TRUE(clipped.output.cryptomatte.enabled) << method;
    }
}

TEST(JobLoader, DefaultsWhenOptionalSectionsAreAbsent) {
    const RenderJob job = loadJobFromText(minimalYaml(), "/nonexistent/m.yaml");
    const RenderJob defaults;
    EXPECT_EQ(job.scene.film.width, defaults.scene.film.width);
    EXPECT_EQ(job.render.samples, defaults.render.samples);
    EXPECT_EQ(job.render.subframes, 0);
    EXPECT_EQ(job.render.time_integration, TimeIntegration::Auto);
    EXPECT_EQ(job.render.sweep_time, SweepTime::Points);
    ASSERT_EQ(job.scene.materials.size(), 1u);
    EXPECT_EQ(job.scene.objects[0].name, "object0");
    EXPECT_EQ(job.scene.objects[0].mesh.triangles.size(), 12u);
}

// Each error class, with the exact location, in both front-ends.
// `at` is a substring that occurs once in `text`; the error must point at its first character.
// The expected line and column are counted here from the text, independently of the readers.
struct ErrorCase {
    const char* name;
    std::string file;
    std::string text;
    ExitCode code;
    std::string at;
    const char* message_part;
};

std::pair<int, int> lineColumnOf(const std::string& text, const std::string& at) {
    const std::size_t offset = text.find(at);
    EXPECT_NE(offset, std::string::npos) << at;
    EXPECT_EQ(text.find(at, offset + 1), std::string::npos) << "marker not unique: " << at;
    int line = 1, column = 1;
    for (std::size_t i = 0; i < offset; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return {line, column};
}

class JobErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(JobErrors, ReportedAtLocation) {
    const ErrorCase& c = GetParam();
    const Error e = catchError([&] { loadJobFromText(c.text, c.file); });
    EXPECT_EQ(e.code(), c.code) << e.what();
    EXPECT_EQ(e.loc().file, c.file) << e.what();
    const auto [line, column] = lineColumnOf(c.text, c.at);
    EXPECT_EQ(e.loc().line, line) << e.what();
    EXPECT_EQ(e.loc().column, column) << e.what();
    EXPECT_NE(e.message().find(c.message_part), std::string::npos) << e.what();
}

const std::string kBox = "  - primitive: {type: box}\n";
const std::string kCam = "camera:\n  keys:\n    - {time: 0, position: [0, 0, -5]}\n";

INSTANTIATE_TEST_SUITE_P(
    Yaml, JobErrors,
    ::testing::Values(
        ErrorCase{"UnknownKey", "e.yaml", minimalYaml("film: {widht: 3}\n"), ExitCode::Config, "widht", "unknown key 'film.widht'"},
        ErrorCase{"WrongType", "e.yaml", minimalYaml("film: {width: wide}\n"), ExitCode::Config, "wide", "must be an integer"},
        ErrorCase{"QuotedNumber", "e.yaml", minimalYaml("render: {samples: '4'}\n"), ExitCode::Config, "'4'", "must be an integer"},
        ErrorCase{"MissingRequired", "e.yaml", "version: 1\nobjects:\n" + kBox, ExitCode::Config, "version", "missing required key 'camera'"},
        ErrorCase{"MissingRequiredNested", "e.yaml", "version: 1\ncamera: {vfov: 30}\nobjects:\n" + kBox, ExitCode::Config, "{vfov", "missing required key 'camera.keys'"},
        ErrorCase{"BadVersion", "e.yaml", "version: 2\n", ExitCode::Config, "2", "version"},
        ErrorCase{"OutOfRange", "e.yaml", minimalYaml("shutter: {open: 1.5}\n"), ExitCode::Config, "1.5", "must be in [-1, 1]"},
        ErrorCase{"OpenBeforeRange", "e.yaml", minimalYaml("shutter: {open: -1.5, close: 0}\n"), ExitCode::Config, "-1.5", "must be in [-1, 1]"},
        ErrorCase{"ShutterLongerThanAFrame", "e.yaml", minimalYaml("shutter: {open: -0.5, close: 0.75}\n"), ExitCode::Config, "0.75}", "longer than a frame"},
        ErrorCase{"ShutterUnknownKey", "e.yaml", minimalYaml("shutter: {open: 0, curv: []}\n"), ExitCode::Config, "curv", "unknown key 'shutter.curv'"},
        ErrorCase{"CurveOnePoint", "e.yaml", minimalYaml("shutter: {curve: [[0, 1]]}\n"), ExitCode::Config, "[[0, 1]]", "at least two points"},
        ErrorCase{"CurvePointNotAPair", "e.yaml", minimalYaml("shutter: {curve: [[0, 1, 2], [1, 1]]}\n"), ExitCode::Config, "[0, 1, 2]", "[time, weight]"},
        ErrorCase{"CurveNotFromOpen", "e.yaml", minimalYaml("shutter: {open: -0.25, close: 0.25, curve: [[-0.2, 1], [0.25, 1]]}\n"),
                  ExitCode::Config, "-0.2,", "start the curve at 'shutter.open' (-0.25)"},
        ErrorCase{"CurveNotToClose", "e.yaml", minimalYaml("shutter: {curve: [[0, 1], [0.9, 1]]}\n"), ExitCode::Config, "0.9", "end the curve at 'shutter.close' (1)"},
        ErrorCase{"CurveTimesNotIncreasing", "e.yaml", minimalYaml("shutter: {curve: [[0, 1], [0.5, 1], [0.5, 2], [1, 1]]}\n"),
                  ExitCode::Config, "0.5, 2", "come after the point before it"},
        ErrorCase{"CurveNegativeWeight", "e.yaml", minimalYaml("shutter: {curve: [[0, 1], [1, -2]]}\n"), ExitCode::Config, "-2", "'shutter.curve[1].weight' must be in [0,"},
        ErrorCase{"CurveAllZero", "e.yaml", minimalYaml("shutter: {curve: [[0, 0], [0.5, 0], [1, 0]]}\n"), ExitCode::Config, "[[0, 0]", "no positive weight"},
        ErrorCase{"CurveTimeOutOfRange", "e.yaml", minimalYaml("shutter: {curve: [[0, 1], [1.5, 1]]}\n"), ExitCode::Config, "1.5", "must be in [-1, 1]"},
        ErrorCase{"CloseBeforeOpen", "e.yaml", minimalYaml("shutter: {open: 0.5, close: 0.25}\n"), ExitCode::Config, "0.25", "not be before"},
        ErrorCase{"HugeWidth", "e.yaml", minimalYaml("film: {width: 100000}\n"), ExitCode::Config, "100000", "16384"},
        ErrorCase{"MeshTooBig", "e.yaml", "version: 1\n" + kCam + "objects:\n  - primitive: {type: grid, divisions: 4096}\n",
                  ExitCode::Config, "{type: grid", "triangles"},
        ErrorCase{"DuplicateKey", "e.yaml", minimalYaml("film: {width: 3, width: 4}\n"), ExitCode::Config, "width: 4", "duplicate key"},
        ErrorCase{"UnknownEnum", "e.yaml", minimalYaml("render: {method: magic}\n"), ExitCode::Config, "magic", "one of clipped"},
        ErrorCase{"UnknownSweepTime", "e.yaml", minimalYaml("render: {sweep_time: chords}\n"), ExitCode::Config, "chords", "one of points"},
        ErrorCase{"SubframesAboveMax", "e.yaml", minimalYaml("render: {max_subframes: 8, subframes: 9}\n"), ExitCode::Config, "9}", "[1, 8]"},
        ErrorCase{"ErrorTargetOutOfRange", "e.yaml", minimalYaml("render: {error_target: 0.9}\n"), ExitCode::Config, "0.9}", "must be in [1e-05, 0.5]"},
        ErrorCase{"ErrorTargetWithSpacing", "e.yaml", minimalYaml("render: {time_integration: sweep, sweep_spacing: 2, error_target: 0.001}\n"),
                  ExitCode::Config, "0.001}", "leave 'render.sweep_spacing' out"},
        ErrorCase{"ErrorTargetWithReclipSpacing", "e.yaml", minimalYaml("render: {reclip_spacing: 0.5, error_target: 0.001}\n"),
                  ExitCode::Config, "0.001}", "leave 'render.reclip_spacing' out"},
        ErrorCase{"ErrorTargetWithStochastic", "e.yaml", minimalYaml("render: {method: stochastic, error_target: 0.001}\n"),
                  ExitCode::Config, "0.001}", "is for render.method clipped, not stochastic"},
        ErrorCase{"ErrorTargetWithSpacingUnderAuto", "e.yaml", minimalYaml("render: {sweep_spacing: 2, error_target: 0.003}\n"),
                  ExitCode::Config, "0.003}", "leave 'render.sweep_spacing' out"},
        ErrorCase{"ErrorTargetWithSubframesUnderAuto", "e.yaml",
                  minimalYaml("render: {time_integration: auto, subframes: 4, error_target: 0.004}\n"), ExitCode::Config, "0.004}",
                  "leave 'render.subframes' at auto"},
        ErrorCase{"UnknownTimeIntegration", "e.yaml", minimalYaml("render: {time_integration: smart}\n"), ExitCode::Config, "smart",
                  "one of subframes, sweep, auto"},
        ErrorCase{"ErrorTargetWithSubframes", "e.yaml", minimalYaml("render: {subframes: 8, error_target: 0.002}\n"), ExitCode::Config, "0.002}",
                  "leave 'render.subframes' at auto"},
        ErrorCase{"UnknownMaterial", "e.yaml", "version: 1\n" + kCam + "objects:\n  - {primitive: {type: box}, material: gold}\n", ExitCode::Config, "gold", "unknown material"},
        ErrorCase{"NonFinite", "e.yaml", minimalYaml("ambient: .nan\n"), ExitCode::Config, ".nan", "finite"},
        ErrorCase{"UnsortedCameraKeys", "e.yaml", "version: 1\ncamera:\n  keys:\n    - {time: 1}\n    - {time: 0.5}\nobjects:\n" + kBox, ExitCode::Scene, "{time: 0.5}", "sorted"},
        ErrorCase{"UnsortedTransformKeys", "e.yaml", "version: 1\n" + kCam + "objects:\n  - primitive: {type: box}\n    transform:\n      - {time: 0}\n      - {time: 0, translate: [1, 0, 0]}\n",
                  ExitCode::Scene, "{time: 0, translate", "sorted"},
        ErrorCase{"ViewParallelToUp", "e.yaml", "version: 1\ncamera:\n  keys:\n    - {view: [0, 2, 0], position: [0, 0, -5]}\nobjects:\n" + kBox, ExitCode::Config, "{view", "parallel"},
        ErrorCase{"ZeroView", "e.yaml", "version: 1\ncamera:\n  keys:\n    - {view: [0, 0, 0]}\nobjects:\n" + kBox, ExitCode::Config, "[0, 0, 0]", "zero vector"},
        ErrorCase{"EmptyScene", "e.yaml", "version: 1\n" + kCam + "objects: []\n", ExitCode::Scene, "[]", "no objects"},
        ErrorCase{"MissingObj", "e.yaml", "version: 1\n" + kCam + "objects:\n  - obj: nowhere.obj\n", ExitCode::Scene, "nowhere.obj", "nowhere.obj"},
        ErrorCase{"PrimitiveAndObj", "e.yaml", "version: 1\n" + kCam + "objects:\n  - {primitive: {type: box}, obj: x.obj}\n", ExitCode::Config, "x.obj", "both"},
        ErrorCase{"BadCompression", "e.yaml", minimalYaml("output: {compression: lzma}\n"), ExitCode::Config, "lzma", "one of zip"},
        ErrorCase{"BadBackground", "e.yaml", minimalYaml("output: {background: sky}\n"), ExitCode::Config, "sky", "one of separate"},
        ErrorCase{"CryptomatteWithDwaa", "e.yaml", minimalYaml("render: {method: stochastic}\noutput: {compression: dwaa, cryptomatte: {}}\n"),
                  ExitCode::Config, "dwaa", "corrupt Cryptomatte"},
        ErrorCase{"CryptomatteLayerName", "e.yaml", minimalYaml("render: {method: stochastic}\noutput: {cryptomatte: {name: a.b}}\n"),
                  ExitCode::Config, "a.b", "A-Z"},
        ErrorCase{"MaterialUnknownKey", "e.yaml", minimalYaml("materials: [{name: m, emisson: 1}]\n"), ExitCode::Config, "emisson", "unknown key 'materials[0].emisson'"},
        ErrorCase{"NegativeEmission", "e.yaml", minimalYaml("materials: [{name: m, emission: [1, -0.5, 0]}]\n"), ExitCode::Config, "-0.5", "'materials[0].emission[1]' must be in [0,"},
        ErrorCase{"EmissionNotANumber", "e.yaml", minimalYaml("materials: [{name: m, emission: bright}]\n"), ExitCode::Config, "bright", "'materials[0].emission'"},
        ErrorCase{"UnlitNotABool", "e.yaml", minimalYaml("materials: [{name: m, unlit: 1}]\n"), ExitCode::Config, "1}", "true or false"},
        ErrorCase{"EmissionOnUnlit", "e.yaml", minimalYaml("materials:\n  - {name: m, unlit: true, emission: 2}\n"), ExitCode::Config, "2}", "'materials[0].emission' has no effect on an unlit material"},
        ErrorCase{"LightKeyOfOtherType", "e.yaml", minimalYaml("lights: [{type: point, position: [0, 0, 0], direction: [0, 0, 1]}]\n"), ExitCode::Config, "direction", "unknown key 'lights[0].direction'"}),
    [](const auto& info) { return std::string(info.param.name); });

const std::string kJsonHead = "{\"version\": 1,\n \"camera\": {\"keys\": [{\"position\": [0, 0, -5]}]},\n";
const std::string kJsonBox = " \"objects\": [{\"primitive\": {\"type\": \"box\"}}]";

INSTANTIATE_TEST_SUITE_P(
    Json, JobErrors,
    ::testing::Values(
        ErrorCase{"UnknownKey", "e.json", kJsonHead + " \"objects\": [{\"primitive\": {\"type\": \"box\"}, \"colour\": 1}]}", ExitCode::Config, "\"colour\"", "unknown key 'objects[0].colour'"},
        ErrorCase{"WrongType", "e.json", kJsonHead + " \"objects\": [{\"primitive\": {\"type\": \"box\", \"size\": \"2\"}}]}", ExitCode::Config, "\"2\"", "must be a number"},
        ErrorCase{"MissingRequired", "e.json", "{\"version\": 1,\n \"objects\": []}", ExitCode::Config, "{\"version\"", "missing required key 'camera'"},
        ErrorCase{"OutOfRange", "e.json", kJsonHead + " \"objects\": [{\"primitive\": {\"type\": \"sphere\", \"segments\": 2}}]}", ExitCode::Config, "2}", "must be in [3, 4096]"},
        ErrorCase{"HugeWidth", "e.json", kJsonHead + " \"film\": {\"width\": 16385},\n" + kJsonBox + "}", ExitCode::Config, "16385", "16384"},
        ErrorCase{"DuplicateKey", "e.json", kJsonHead + kJsonBox + ",\n \"objects\": []}", ExitCode::Config, "\"objects\": []", "duplicate key"},
        ErrorCase{"Syntax", "e.json", kJsonHead + " \"objects\": @}", ExitCode::Config, "@", "JSON syntax error"},
        ErrorCase{"UnsortedCameraKeys", "e.json", "{\"version\": 1,\n \"camera\": {\"keys\": [{\"time\": 2},\n   {\"time\": 1}]},\n" + kJsonBox + "}", ExitCode::Scene, "{\"time\": 1}", "sorted"},
        ErrorCase{"ViewParallelToUp", "e.json", "{\"version\": 1,\n \"camera\": {\"keys\": [{\"view\": [0, -1, 0]}]},\n" + kJsonBox + "}", ExitCode::Config, "{\"view\"", "parallel"},
        ErrorCase{"EmissionOnUnlit", "e.json", kJsonHead + " \"materials\": [{\"name\": \"m\", \"emission\": [0, 1, 0],\n   \"unlit\": true}],\n" + kJsonBox + "}",
                  ExitCode::Config, "[0, 1, 0]", "has no effect on an unlit material"},
        ErrorCase{"BoolAsString", "e.json", kJsonHead + " \"render\": {\"shadows\": \"true\"},\n" + kJsonBox + "}", ExitCode::Config, "\"true\"", "true or false"}),
    [](const auto& info) { return std::string(info.param.name); });

// A centred 180-degree shutter with a trapezoid curve, the example of docs/config.md, in both spellings.
// Every time integration is read by name, and the error target sits beside the one setting it leaves free.
TEST(JobLoader, TimeIntegrationByName) {
    const struct {
        const char* yaml;
        TimeIntegration expected;
    } cases[] = {{"render: {time_integration: subframes}\n", TimeIntegration::Subframes},
                 {"render: {time_integration: sweep}\n", TimeIntegration::Sweep},
                 {"render: {time_integration: auto}\n", TimeIntegration::Auto},
                 {"render: {time_integration: auto, error_target: 0.002, max_subframes: 64}\n", TimeIntegration::Auto},
                 {"render: {time_integration: subframes, sweep_spacing: 2, error_target: 0.002}\n", TimeIntegration::Subframes},
                 {"render: {time_integration: sweep, subframes: 3, error_target: 0.002}\n", TimeIntegration::Sweep}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.yaml);
        EXPECT_EQ(loadJobFromText(minimalYaml(c.yaml), "/nonexistent/m.yaml").render.time_integration, c.expected);
    }
}

TEST(JobLoader, CentredShutterWithCurveIsAccepted) {
    const RenderJob yaml = loadJobFromText(
        minimalYaml("shutter:\n  open: -0.25\n  close: 0.25\n  curve: [[-0.25, 0], [-0.15, 1], [0.15, 1], [0.25, 0]]\n"),
        "c.yaml");
    EXPECT_EQ(yaml.shutter.open, -0.25);
    EXPECT_EQ(yaml.shutter.close, 0.25);
    ASSERT_EQ(yaml.shutter.curve.size(), 4u);
    EXPECT_EQ(yaml.shutter.curve[1].time, -0.15);
    EXPECT_EQ(yaml.shutter.curve[1].weight, 1.0);
    EXPECT_EQ(yaml.shutter.curve[3].weight, 0.0);
    const RenderJob json = loadJobFromText(
        kJsonHead + " \"shutter\": {\"open\": -0.25, \"close\": 0.25, \"curve\": [[-0.25, 0], [-0.15, 1], [0.15, 1], "
                    "[0.25, 0]]},\n" + kJsonBox + "}",
        "c.json");
    ASSERT_EQ(json.shutter.curve.size(), 4u);
    EXPECT_EQ(json.shutter.curve[2].time, 0.15);
    // Open past -1 + 1 frame: a whole frame's shutter ending at the frame is the longest allowed.
    const RenderJob whole = loadJobFromText(minimalYaml("shutter: {open: -1, close: 0}\n"), "w.yaml");
    EXPECT_EQ(whole.shutter.open, -1.0);
    EXPECT_TRUE(whole.shutter.curve.empty());
}

TEST(JobLoader, LargestFilmIsAccepted) {
    // Both side caps are inclusive; their product, 2^28 pixels, is the largest film.
    const RenderJob job = loadJobFromText(minimalYaml("film: {width: 16384, height: 16384}\n"), "big.yaml");
    EXPECT_EQ(static_cast<long long>(job.scene.film.width) * job.scene.film.height, 1ll << 28);
}

TEST(JobLoader, AbsurdObjCoordinateIsASceneErrorInTheObjFile) {
    const auto dir = testDir();
    // Located in the OBJ file, naming where the job refers to it.
    writeFile(dir / "inf.obj", "v 0 0 0\nv 1e400 0 0\nv 0 1 0\nf 1 2 3\n");
    writeFile(dir / "far.obj", "v 0 0 0\nv 2e8 0 0\nv 0 1 0\nf 1 2 3\n");
    writeFile(dir / "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    for (const char* obj : {"inf.obj", "far.obj", "nan.obj"}) {
        const auto job = writeFile(dir / "j.yaml", "version: 1\ncamera: {keys: [{}]}\nobjects:\n  - name: bad\n    obj: " +
                                                       std::string(obj) + "\n");
        const Error e = catchError([&] { loadJob(job); });
        EXPECT_EQ(e.code(), ExitCode::Scene) << e.what();
        EXPECT_EQ(e.loc().toString(), (dir / obj).string() + ":2:3") << e.what();
        EXPECT_NE(e.message().find((dir / "j.yaml").string() + ":5:10"), std::string::npos) << e.what();
    }
}

TEST(JobLoader, DeformationWithOtherTopologyIsRefused) {
    const auto dir = testDir();
    writeFile(dir / "tri.obj", kTriangleObj);
    writeFile(dir / "one.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const auto job = writeFile(dir / "j.yaml", "version: 1\ncamera: {keys: [{}]}\nobjects:\n  - obj: tri.obj\n"
                                               "    deformation:\n      - {time: 1, obj: one.obj}\n");
    const Error e = catchError([&] { loadJob(job); });
    EXPECT_EQ(e.code(), ExitCode::Scene);
    EXPECT_EQ(e.loc().toString(), (dir / "j.yaml").string() + ":6:24");
    EXPECT_NE(e.message().find("topology"), std::string::npos);
}

// A quad bent non-convex at a key is split along the diagonal its shape needs there, yet it is the same
// face: the key is accepted and moves the object's own triangles (found with the bench's bending limbs).
TEST(JobLoader, DeformationKeyWithTheSameFacesSplitOtherwiseIsAccepted) {
    const auto dir = testDir();
    const std::string square = "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\n";
    // Vertex 1, then vertex 2, pushed inwards: each dart admits one diagonal only, so one of them
    // differs from the square's split whichever diagonal that takes.
    const std::vector<std::string> darts{"v 1.5 1.5 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\n",
                                         "v 0 0 0\nv 0.8 1 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\n"};
    const Mesh base = parseObjMesh(square, "square.obj", FileLoc{}, 16);
    int split_otherwise = 0;
    for (std::size_t k = 0; k < darts.size(); ++k) {
        SCOPED_TRACE(darts[k]);
        split_otherwise += parseObjMesh(darts[k], "dart.obj", FileLoc{}, 16).triangles != base.triangles;
        writeFile(dir / "square.obj", square);
        writeFile(dir / "dart.obj", darts[k]);
        const auto job = writeFile(dir / "j.yaml", "version: 1\ncamera: {keys: [{}]}\nobjects:\n  - obj: square.obj\n"
                                                   "    deformation:\n      - {time: 0, obj: square.obj}\n"
                                                   "      - {time: 1, obj: dart.obj}\n");
        const RenderJob loaded = loadJob(job);
        const Object& object = loaded.scene.objects.at(0);
        EXPECT_EQ(object.mesh.triangles, base.triangles);
        ASSERT_EQ(object.deformation.size(), 2u);
        EXPECT_EQ(object.deformation[1].positions, parseObjMesh(darts[k], "dart.obj", FileLoc{}, 16).positions);
    }
    EXPECT_GE(split_otherwise, 1) << "neither key exercises a different split";
    // Other faces are still another topology, though the triangle count matches.
    writeFile(dir / "dart.obj", "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 2 3 4 1\n");
    const Error e = catchError([&] { loadJob(dir / "j.yaml"); });
    EXPECT_EQ(e.code(), ExitCode::Scene);
    EXPECT_NE(e.message().find("topology"), std::string::npos);
}

TEST(JobLoader, DegenerateTrianglesAreKeptAndReported) {
    const auto dir = testDir();
    // Triangle 2 repeats a vertex, triangle 3 is collinear.
    writeFile(dir / "d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\nf 1 2 4\n");
    const RenderJob job = loadJob(writeFile(dir / "j.yaml", "version: 1\ncamera: {keys: [{position: [0, 0, -3]}]}\nobjects:\n  - obj: d.obj\n"));
    EXPECT_EQ(job.scene.objects[0].mesh.triangles.size(), 3u);
    ASSERT_EQ(job.warnings.size(), 1u);
    EXPECT_NE(job.warnings[0].find("2 degenerate"), std::string::npos) << job.warnings[0];
}

TEST(JobLoader, CameraInsideClosedObjectWarns) {
    const RenderJob job = loadJobFromText(
        "version: 1\ncamera: {keys: [{position: [0.1, 0, 0]}]}\nobjects:\n  - primitive: {type: box, size: 2}\n", "w.yaml");
    ASSERT_EQ(job.warnings.size(), 1u);
    EXPECT_NE(job.warnings[0].find("w.yaml:2:17: camera key 0 is inside"), std::string::npos) << job.warnings[0];
    // Just outside the box: no warning.
    EXPECT_TRUE(loadJobFromText("version: 1\ncamera: {keys: [{position: [0, 0, -1.01]}]}\nobjects:\n"
                                "  - primitive: {type: box, size: 2}\n", "w.yaml")
                    .warnings.empty());
}

TEST(JobLoader, OverridesApplyBeforeValidationAndChangeTheHash) {
    const RenderJob base = loadJobFromText(minimalYaml(), "o.yaml");
    const RenderJob job = loadJobFromText(minimalYaml(), "o.yaml", {"render.samples=64", "film.width=320"});
    EXPECT_EQ(job.render.samples, 64);
    EXPECT_EQ(job.scene.film.width, 320);
    EXPECT_NE(job.config_hash, base.config_hash);
    const Error bad_type = catchError([] { loadJobFromText(minimalYaml(), "o.yaml", {"render.samples=many"}); });
    EXPECT_EQ(bad_type.loc().toString(), "<--set>:1:16");
    const Error unknown = catchError([] { loadJobFromText(minimalYaml(), "o.yaml", {"render.smaples=4"}); });
    EXPECT_EQ(unknown.loc().toString(), "<--set>:1:8");
    EXPECT_NE(unknown.message().find("unknown key 'render.smaples'"), std::string::npos);
}

TEST(JobLoader, EveryShippedConfigLoads) {
    int count = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(CLIPBLUR_SOURCE_DIR) + "/configs")) {
        const auto ext = entry.path().extension();
        if (entry.path().parent_path().filename() == "schema" || (ext != ".yaml" && ext != ".json")) continue;
        SCOPED_TRACE(entry.path().string());
        if (entry.path().parent_path().filename() == "refused") {  // shipped to show a clean refusal
            try {
                loadJob(entry.path());
                ADD_FAILURE() << "expected a scene error";
            } catch (const Error& e) {
                EXPECT_EQ(e.code(), ExitCode::Scene);
            }
            continue;
        }
        const RenderJob job = loadJob(entry.path());
        EXPECT_TRUE(job.warnings.empty());
        EXPECT_EQ(job.render.method, Method::Clipped);
        ++count;
    }
    EXPECT_GE(count, 6);
}

TEST(ValidateCommand, ExitCodesAndSummary) {
    const auto dir = testDir();
    const std::string bin = CLIPBLUR_BINARY;
    const auto run = [&](const std::string& args) {
        const int status = std::system((bin + " validate " + args + " > " + (dir / "out.txt").string() + " 2>&1").c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    EXPECT_EQ(run(std::string(CLIPBLUR_SOURCE_DIR) + "/configs/default.yaml"), 0);
    std::ifstream in(dir / "out.txt");
    const std::string out((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(out.find("objects:      3"), std::string::npos) << out;
    EXPECT_EQ(run(writeFile(dir / "c.yaml", minimalYaml("film: {widht: 3}\n")).string()), 3);
    EXPECT_EQ(run(writeFile(dir / "s.yaml", "version: 1\ncamera: {keys: [{}]}\nobjects: []\n").string()), 4);
    EXPECT_EQ(run(writeFile(dir / "ok.yaml", minimalYaml()).string() + " --set render.samples=0"), 3);
}

}  // namespace clipblur
