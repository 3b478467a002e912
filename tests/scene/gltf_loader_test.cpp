#include "scene/gltf_loader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "renderer/camera_path.h"
#include "renderer/frame_motion.h"
#include "renderer/propagation/surface_path.h"
#include "scene/camera.h"
#include "scene/exact_camera.h"
#include "scene/exact_motion.h"
#include "scene/object_motion.h"
#include "support/gltf_writer.h"
#include "support/texture_files.h"

namespace clipblur {

namespace {

using testing::GltfWriter;
using nlohmann::json;

constexpr double kHalfPi = 1.5707963267948966;

// A tetrahedron: four corners spanning each axis, so a pose error shows at some vertex.
const std::vector<glm::dvec3> kTetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

int addTetraMesh(GltfWriter& w, int index_type = 5123) {
    std::vector<float> p;
    for (const glm::dvec3& v : kTetra) p.insert(p.end(), {float(v.x), float(v.y), float(v.z)});
    const int pos = w.addFloats(p, "VEC3", 34962);
    const int idx = w.addIndices({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, index_type);
    w.doc()["meshes"].push_back({{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}})}});
    return static_cast<int>(w.doc()["meshes"].size()) - 1;
}

int addNode(GltfWriter& w, json node) {
    w.doc()["nodes"].push_back(std::move(node));
    return static_cast<int>(w.doc()["nodes"].size()) - 1;
}

void setScene(GltfWriter& w, std::vector<int> roots) {
    w.doc()["scene"] = 0;
    w.doc()["scenes"] = json::array({{{"nodes", roots}}});
}

// One channel of a new animation; `values` per key as glTF stores them (x y z w for rotations).
void animate(GltfWriter& w, int node, const std::string& path, const std::string& interpolation,
             const std::vector<float>& times, const std::vector<float>& values) {
    const int in = w.addFloats(times, "SCALAR");
    const std::string type = path == "rotation" ? "VEC4" : path == "weights" ? "SCALAR" : "VEC3";
    const int out = w.addFloats(values, type);
    w.doc()["animations"].push_back(
        {{"samplers", json::array({{{"input", in}, {"output", out}, {"interpolation", interpolation}}})},
         {"channels", json::array({{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}})}});
}

GltfRequest request() {
    GltfRequest r;
    r.ref = FileLoc{"job.yaml", 3, 8};
    r.fps = 24.0;
    r.frames = {0, 0, 24.0};
    r.max_triangles = 1u << 20;
    r.max_transform_keys = 4096;
    r.max_deformation_keys = 129;
    return r;
}

// Writes the asset where the Khronos validator checks it (ctest gltf_validator), then loads it.
GltfScene loadValid(const GltfWriter& w, const std::string& name, const GltfRequest& r = request()) {
    const auto file = testing::validatedAssetDir() / (name + ".gltf");
    w.writeGltf(file);
    return loadGltfScene(file, r);
}

glm::dmat4 trs(glm::dvec3 t, glm::dquat r, glm::dvec3 s) {
    return glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(r) * glm::scale(glm::dmat4(1.0), s);
}

glm::dvec3 apply(const glm::dmat4& m, const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }

// Largest distance between the object's vertices at `times` and the tetrahedron under truth(t).
double worstDeviation(const Object& o, const std::function<glm::dmat4(double)>& truth, const std::vector<double>& times) {
    double worst = 0.0;
    for (const double t : times)
        for (std::uint32_t i = 0; i < kTetra.size(); ++i)
            worst = std::max(worst, glm::length(evalVertex(o, i, t) - apply(truth(t), kTetra[i])));
    return worst;
}

std::vector<double> seededTimes(double t0, double t1, int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(t0, t1);
    std::vector<double> times{t0, t1};
    for (int i = 0; i < n; ++i) times.push_back(u(rng));
    return times;
}

std::vector<float> quat(double angle_deg, glm::dvec3 axis) {
    const glm::dquat q = glm::angleAxis(glm::radians(angle_deg), glm::normalize(axis));
    return {float(q.x), float(q.y), float(q.z), float(q.w)};
}

glm::dquat toQuat(const std::vector<float>& v, std::size_t at = 0) {
    return glm::normalize(glm::dquat(v[at + 3], v[at], v[at + 1], v[at + 2]));
}

}  // namespace

TEST(GltfLoader, StaticHierarchyFoldsTheNodeMatricesIntoTheMesh) {
    GltfWriter w;
    const int mesh = addTetraMesh(w, 5121);
    const std::vector<float> r = quat(30, {1, 2, 3});
    // Non-uniform scale under a rotation is fine when nothing moves: the world matrix is folded in.
    const int child = addNode(w, {{"name", "leaf"}, {"mesh", mesh}, {"translation", {1, 2, 3}}, {"scale", {2, 1, 0.5}}});
    const int parent = addNode(w, {{"name", "root"}, {"children", {child}}, {"rotation", r}});
    const int top = addNode(w, {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1}}, {"children", {parent}}});
    setScene(w, {top});
    const GltfScene s = loadValid(w, "static_hierarchy");
    ASSERT_EQ(s.objects.size(), 1u);
    const Object& o = s.objects[0];
    EXPECT_EQ(o.name, "leaf");
    EXPECT_TRUE(o.transform.empty());
    const glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(5, 0, 0)) * trs({}, toQuat(r), glm::dvec3(1)) *
                         trs({1, 2, 3}, glm::dquat(1, 0, 0, 0), {2, 1, 0.5});
    // 1e-6: the rotation is stored as float.
    for (std::size_t i = 0; i < kTetra.size(); ++i) EXPECT_LT(glm::length(o.mesh.positions[i] - apply(m, kTetra[i])), 1e-6);
    EXPECT_EQ(o.mesh.triangles.size(), 4u);
    EXPECT_EQ(s.materials.size(), 1u);  // the spec's default material
    EXPECT_FALSE(s.materials[o.material].two_sided);
}

TEST(GltfLoader, LinearTrsUnderAStaticUniformParentIsExactAtTheKeyTimes) {
    GltfWriter w;
    const int mesh = addTetraMesh(w, 5125);
    const int child = addNode(w, {{"name", "box"}, {"mesh", mesh}});
    const std::vector<float> pr = quat(-40, {0, 1, 1});
    const int parent = addNode(w, {{"children", {child}}, {"translation", {1, -2, 0.5}}, {"rotation", pr}, {"scale", {2, 2, 2}}});
    setScene(w, {parent});
    animate(w, child, "translation", "LINEAR", {0, 1}, {0, 0, 0, 2, 0, 0});
    std::vector<float> rot = quat(0, {0, 1, 0});
    const std::vector<float> r1 = quat(90, {0, 1, 0});
    rot.insert(rot.end(), r1.begin(), r1.end());
    animate(w, child, "rotation", "LINEAR", {0, 1}, rot);
    animate(w, child, "scale", "LINEAR", {0, 0.5, 1}, {1, 1, 1, 1, 3, 1, 2, 2, 2});
    const GltfScene s = loadValid(w, "linear_trs");
    ASSERT_EQ(s.objects.size(), 1u);
    const Object& o = s.objects[0];
    ASSERT_EQ(o.transform.size(), 3u);  // the union of the key times, 0, 12 and 24 frames: nothing added
    EXPECT_DOUBLE_EQ(o.transform[1].time, 12.0);
    // Hand pose at 6 frames (0.25 s): translation (0.5, 0, 0), 22.5 degrees about y, scale (1, 2, 1).
    const glm::dmat4 parent_m = trs({1, -2, 0.5}, toQuat(pr), glm::dvec3(2));
    const glm::dmat4 at6 = parent_m * trs({0.5, 0, 0}, glm::angleAxis(glm::radians(22.5), glm::dvec3(0, 1, 0)), {1, 2, 1});
    for (std::uint32_t i = 0; i < 4; ++i) EXPECT_LT(glm::length(evalVertex(o, i, 6.0) - apply(at6, kTetra[i])), 1e-6);
    // Everywhere: the glTF motion evaluated independently (lerp, slerp of the key values, matrix product).
    const auto truth = [&](double t) {
        const double u = std::clamp(t / 24.0, 0.0, 1.0);
        const glm::dvec3 scale = u < 0.5 ? glm::mix(glm::dvec3(1), glm::dvec3(1, 3, 1), 2 * u)
                                         : glm::mix(glm::dvec3(1, 3, 1), glm::dvec3(2), 2 * u - 1);
        return parent_m * trs({2 * u, 0, 0}, glm::slerp(toQuat(rot), toQuat(rot, 4), u), scale);
    };
    // 1e-9 of a size-4 object: exact up to rounding (float-stored key values are the same in both).
    EXPECT_LT(worstDeviation(o, truth, seededTimes(-5, 30, 400, 7)), 1e-9);
}

TEST(GltfLoader, StaticChildUnderAnAnimatedParentIsFoldedAndExact) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int child = addNode(w, {{"name", "offset"}, {"mesh", mesh}, {"translation", {3, 0, 0}}, {"scale", {1, 2, 1}}});
    const int parent = addNode(w, {{"name", "spinner"}, {"children", {child}}});
    setScene(w, {parent});
    std::vector<float> rot = quat(0, {0, 0, 1});
    for (const double a : {120.0, 240.0}) {
        const std::vector<float> q = quat(a, {0, 0, 1});
        rot.insert(rot.end(), q.begin(), q.end());
    }
    animate(w, parent, "rotation", "LINEAR", {0, 1, 2}, rot);
    const GltfScene s = loadValid(w, "static_child");
    const Object& o = s.objects.at(0);
    EXPECT_EQ(o.transform.size(), 3u);
    const auto truth = [&](double t) {
        const double k = std::clamp(t / 24.0, 0.0, 2.0);
        const std::size_t i = k >= 1.0 ? 1 : 0;
        const glm::dquat q = glm::slerp(toQuat(rot, 4 * i), toQuat(rot, 4 * i + 4), k - double(i));
        return trs({}, q, glm::dvec3(1)) * trs({3, 0, 0}, glm::dquat(1, 0, 0, 0), {1, 2, 1});
    };
    EXPECT_LT(worstDeviation(o, truth, seededTimes(0, 48, 400, 11)), 1e-9);
}

TEST(GltfLoader, StepHoldsEachKeyUntilTheNext) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int node = addNode(w, {{"name", "stepper"}, {"mesh", mesh}});
    setScene(w, {node});
    animate(w, node, "translation", "STEP", {0, 1, 2}, {0, 0, 0, 1, 0, 0, 3, 0, 0});
    GltfRequest r = request();
    r.frames = {0, 1, 24.0};
    r.shutter = {0.0, 0.5, {}};  // frames 0 and 1 see (0, 0.5) and (1, 1.5); the jumps at 24 and 48 lie outside
    const Object o = loadValid(w, "step", r).objects.at(0);
    for (const auto& [t, x] : std::vector<std::pair<double, double>>{
             {0, 0}, {12, 0}, {23.99, 0}, {24, 1}, {36, 1}, {47.99, 1}, {48, 3}, {100, 3}})
        EXPECT_NEAR(evalVertex(o, 0, t).x, x, 1e-12) << "t = " << t;
    // Inside a jump window the keys move linearly; the window is kStepWindowFrames wide, before the jump.
    EXPECT_NEAR(o.transform[1].time, 24.0 - 1e-3, 1e-12);
}

TEST(GltfLoader, StepJumpInsideARenderedShutterIsRefused) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int node = addNode(w, {{"name", "stepper"}, {"mesh", mesh}});
    setScene(w, {node});
    animate(w, node, "translation", "STEP", {0, 0.5f / 24}, {0, 0, 0, 1, 0, 0});
    try {
        loadValid(w, "step_in_shutter");
        FAIL() << "loaded";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_NE(std::string(e.what()).find("step_in_shutter.gltf: /nodes/0: a STEP key jumps"), std::string::npos) << e.what();
    }
}

// Frame k's shutter spans [(k + open) / fps, (k + close) / fps] of the glTF timeline, open negative too:
// a jump at 1 s (frame 24) lies after frame 24's 0 .. 0.5 shutter opens but inside its centred one
// (23.75 .. 24.25), and before frame 24 of a shutter that opens there (its window is 1e-3 frames before).
TEST(GltfLoader, CentredShutterMeetsAStepJumpAtItsFrame) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int node = addNode(w, {{"name", "stepper"}, {"mesh", mesh}});
    setScene(w, {node});
    animate(w, node, "translation", "STEP", {0, 1}, {0, 0, 0, 1, 0, 0});
    GltfRequest r = request();
    r.frames = {24, 24, 24.0};
    r.shutter = {0.0, 0.5, {}};
    EXPECT_EQ(loadValid(w, "step_at_frame", r).objects.size(), 1u);
    r.shutter = {-0.25, 0.25, {}};
    try {
        loadValid(w, "step_at_centred_frame", r);
        FAIL() << "loaded";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_NE(std::string(e.what()).find("inside the shutter of frame 24"), std::string::npos) << e.what();
    }
}

TEST(GltfLoader, CubicSplineIsFollowedExactly) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int node = addNode(w, {{"name", "swing"}, {"mesh", mesh}});
    setScene(w, {node});
    // Per key: in-tangent, value, out-tangent (units per second).
    const std::vector<float> tr = {0, 0, 0, 0, 0, 0, 4, 0, 0, /**/ 0, 5, 0, 2, 1, 0, 0, -3, 0};
    animate(w, node, "translation", "CUBICSPLINE", {0, 1}, tr);
    std::vector<float> rot;
    for (const auto& [a, tangent] : std::vector<std::pair<double, float>>{{0, 0.f}, {170, 0.f}}) {
        const std::vector<float> q = quat(a, {1, 1, 0});
        for (int k = 0; k < 4; ++k) rot.push_back(tangent);
        rot.insert(rot.end(), q.begin(), q.end());
        for (int k = 0; k < 4; ++k) rot.push_back(tangent);
    }
    animate(w, node, "rotation", "CUBICSPLINE", {0, 1}, rot);
    const Object o = loadValid(w, "cubic").objects.at(0);
    // Hand value at 0.5 s: Hermite with dt = 1 s, h = (0.5, 0.125, 0.5, -0.125) on (v0, out0, v1, in1).
    const glm::dvec3 mid = 0.5 * glm::dvec3(0) + 0.125 * glm::dvec3(4, 0, 0) + 0.5 * glm::dvec3(2, 1, 0) - 0.125 * glm::dvec3(0, 5, 0);
    const auto hermite = [&](double u) {
        const double h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u;
        const double h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
        const glm::dvec3 t = h10 * glm::dvec3(4, 0, 0) + h01 * glm::dvec3(2, 1, 0) + h11 * glm::dvec3(0, 5, 0);
        // Appendix C interpolates the stored (float, not quite unit) values, then normalises.
        const glm::dquat q0(rot[7], rot[4], rot[5], rot[6]), q1(rot[19], rot[16], rot[17], rot[18]);
        const glm::dquat q = glm::normalize(glm::dquat(h00 * q0.w + h01 * q1.w, h00 * q0.x + h01 * q1.x,
                                                       h00 * q0.y + h01 * q1.y, h00 * q0.z + h01 * q1.z));
        return trs(t, q, glm::dvec3(1));
    };
    EXPECT_LT(glm::length(glm::dvec3(hermite(0.5)[3]) - mid), 1e-12);  // the oracle agrees with the hand value
    const auto truth = [&](double t) { return hermite(std::clamp(t / 24.0, 0.0, 1.0)); };
    ASSERT_TRUE(o.motion);  // no keys: the spline itself
    EXPECT_TRUE(o.transform.empty());
    const double worst = worstDeviation(o, truth, seededTimes(0, 24, 4000, 3));
    // 1e-12 of a unit object: only rounding differs (tangents scaled by 1/fps, then by the interval).
    EXPECT_LT(worst, 1e-12);
    std::cout << "CUBICSPLINE: exact motion, measured deviation " << worst << "\n";
}

TEST(GltfLoader, TwoAnimatedNodesComposeExactly) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int wheel = addNode(w, {{"name", "wheel"}, {"mesh", mesh}, {"translation", {1, 0.5, 0}}});
    const int car = addNode(w, {{"name", "car"}, {"children", {wheel}}});
    setScene(w, {car});
    animate(w, car, "translation", "LINEAR", {0, 2}, {0, 0, 0, 10, 0, 0});
    // The car also turns, so the wheel's offset swings on an arc: not linear in time.
    std::vector<float> turn = quat(0, {0, 1, 0});
    const std::vector<float> turned = quat(90, {0, 1, 0});
    turn.insert(turn.end(), turned.begin(), turned.end());
    animate(w, car, "rotation", "LINEAR", {0, 2}, turn);
    std::vector<float> spin;
    for (const double a : {0.0, -120.0, -240.0, -360.0}) {
        const std::vector<float> q = quat(a, {0, 0, 1});
        spin.insert(spin.end(), q.begin(), q.end());
    }
    animate(w, wheel, "rotation", "LINEAR", {0, 0.5, 1, 1.5}, spin);
    const Object o = loadValid(w, "car_wheel").objects.at(0);
    const auto truth = [&](double t) {
        const double s = std::clamp(t / 24.0, 0.0, 2.0);
        const double k = std::min(s / 0.5, 3.0);
        const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(k), 2);
        glm::dquat a = toQuat(spin, 4 * i), b = toQuat(spin, 4 * i + 4);
        if (glm::dot(a, b) < 0) b = -b;
        return trs({5 * s, 0, 0}, glm::slerp(toQuat(turn), toQuat(turn, 4), s / 2), glm::dvec3(1)) *
               trs({1, 0.5, 0}, glm::slerp(a, b, k - double(i)), glm::dvec3(1));
    };
    ASSERT_TRUE(o.motion);
    const double worst = worstDeviation(o, truth, seededTimes(0, 48, 4000, 5));
    // 1e-12 against a path 10 units long: the same products, rounded in another order.
    EXPECT_LT(worst, 1e-12);
    std::cout << "car and wheel: exact motion, measured deviation " << worst << "\n";
}

// A world matrix with shear: a node turning under a parent stretched along y (transform keys cannot hold
// it). Under it, a CUBICSPLINE translation on the middle node. Positions against the product computed
// here, their rates against central differences, normals by the inverse transpose.
TEST(GltfLoader, ShearedChainIsFollowedExactlyWithItsRatesAndNormals) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int child = addNode(w, {{"name", "crate"}, {"mesh", mesh}, {"translation", {0.5, 0, 0}}});
    const int middle = addNode(w, {{"name", "slider"}, {"children", {child}}});
    const int stretch = addNode(w, {{"name", "stretch"}, {"children", {middle}}, {"translation", {1, 2, 3}}, {"scale", {1, 3, 0.5}}});
    setScene(w, {stretch});
    const std::vector<float> tr = {0, 0, 0, 0, 0, 0, 2, 1, 0, /**/ 0, -3, 0, 1, 1, 1, 0, 0, 0};
    animate(w, middle, "translation", "CUBICSPLINE", {0, 1}, tr);
    std::vector<float> rot = quat(10, {0, 0, 1});
    for (const double a : {80.0, 200.0}) {
        const std::vector<float> q = quat(a, {0.3, 0.2, 1});
        rot.insert(rot.end(), q.begin(), q.end());
    }
    animate(w, child, "rotation", "LINEAR", {0, 0.5, 1}, rot);
    const Object o = loadValid(w, "sheared_chain").objects.at(0);
    ASSERT_TRUE(o.motion);
    const glm::dmat4 stretch_m = trs({1, 2, 3}, glm::dquat(1, 0, 0, 0), {1, 3, 0.5});
    const auto truth = [&](double t) {
        const double u = std::clamp(t / 24.0, 0.0, 1.0);
        const double h10 = u * u * u - 2 * u * u + u, h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
        const glm::dvec3 slide = h10 * glm::dvec3(2, 1, 0) + h01 * glm::dvec3(1, 1, 1) + h11 * glm::dvec3(0, -3, 0);
        const double k = std::min(2.0 * u, 1.999999999999);
        const std::size_t i = static_cast<std::size_t>(k);
        glm::dquat a = toQuat(rot, 4 * i), b = toQuat(rot, 4 * i + 4);
        if (glm::dot(a, b) < 0) b = -b;
        const glm::dquat q = u >= 1.0 ? b : glm::slerp(a, b, k - double(i));
        return stretch_m * trs(slide, glm::dquat(1, 0, 0, 0), glm::dvec3(1)) * trs({0.5, 0, 0}, q, glm::dvec3(1));
    };
    const std::vector<double> times = seededTimes(0, 24, 2000, 19);
    // 1e-12 of a path about 10 long: the same products in another order.
    const double worst = worstDeviation(o, truth, times);
    EXPECT_LT(worst, 1e-12);
    // The matrix does shear: its first two columns are not orthogonal at 6 frames.
    const glm::dmat4 at6 = truth(6.0);
    EXPECT_GT(std::abs(glm::dot(glm::normalize(glm::dvec3(at6[0])), glm::normalize(glm::dvec3(at6[1])))), 0.1);
    double worst_rate = 0.0;
    double worst_normal = 0.0;
    for (const double t : times) {
        if (t <= 1e-3 || t >= 24.0 - 1e-3 || std::abs(t - 12.0) < 1e-3) continue;  // no difference across a key
        const ExactPose pose = o.motion->pose(o.mesh.positions, t, ExactMotion::Rates::Compute);
        for (std::uint32_t v = 0; v < 4; ++v) {
            // Central difference, h = 1e-4 frames: truncation ~h^2 times the third derivative ~ 1e-9,
            // rounding ~1e-16 / h ~ 1e-12.
            const double h = 1e-4;
            const glm::dvec3 fd = (apply(truth(t + h), kTetra[v]) - apply(truth(t - h), kTetra[v])) / (2 * h);
            worst_rate = std::max(worst_rate, glm::length(pose.vertexRate(v) - fd));
        }
        // The face (0, 2, 1)'s normal stays normal to its world edges.
        const glm::dmat3 normals = normalMatrix(o, t);
        const glm::dvec3 n = glm::normalize(normals * glm::cross(kTetra[2] - kTetra[0], kTetra[1] - kTetra[0]));
        for (const auto& [a, b] : std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {1, 2}})
            worst_normal = std::max(worst_normal, std::abs(glm::dot(n, glm::normalize(apply(truth(t), kTetra[b]) -
                                                                                        apply(truth(t), kTetra[a])))));
    }
    // Velocities are about 0.1 to 1 unit per frame; 1e-7 is far above the differences' error and far below
    // a missing term of the product rule.
    EXPECT_LT(worst_rate, 1e-7);
    EXPECT_LT(worst_normal, 1e-12);
    std::cout << "sheared chain: deviation " << worst << ", rate deviation " << worst_rate << ", normal " << worst_normal
              << "\n";
}

// CUBICSPLINE morph weights: positions are base + sum w_i(t) d_i with w from the Hermite spline.
TEST(GltfLoader, CubicSplineMorphWeightsAreFollowedExactly) {
    GltfWriter w;
    std::vector<float> p;
    for (const glm::dvec3& v : kTetra) p.insert(p.end(), {float(v.x), float(v.y), float(v.z)});
    const int pos = w.addFloats(p, "VEC3", 34962);
    const int idx = w.addIndices({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, 5123);
    const int d0 = w.addFloats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1}, "VEC3", 34962);
    const int d1 = w.addFloats({0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 34962);
    w.doc()["meshes"].push_back({{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", idx},
                                                              {"targets", json::array({{{"POSITION", d0}}, {{"POSITION", d1}}})}}})},
                                 {"weights", {0, 0}}});
    const int node = addNode(w, {{"name", "blob"}, {"mesh", 0}});
    setScene(w, {node});
    // Per key: in-tangents (2), values (2), out-tangents (2), per second.
    const std::vector<float> wk = {0, 0, 0, 0, 3, -1, /**/ 1, 2, 1, 0.5f, 0, 0};
    animate(w, node, "weights", "CUBICSPLINE", {0, 1}, wk);
    const Object o = loadValid(w, "cubic_morph").objects.at(0);
    ASSERT_TRUE(o.motion);
    double worst = 0.0;
    for (const double t : seededTimes(0, 24, 1000, 23)) {
        const double u = t / 24.0;
        const double h10 = u * u * u - 2 * u * u + u, h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
        const double w0 = h10 * 3 + h01 * 1 + h11 * 1, w1 = h10 * -1 + h01 * 0.5 + h11 * 2;
        worst = std::max({worst, glm::length(evalVertex(o, 3, t) - glm::dvec3(0, 0, 1 + w0)),
                          glm::length(evalVertex(o, 1, t) - glm::dvec3(1 + w1, 0, 0))});
    }
    EXPECT_LT(worst, 1e-12);  // rounding only
    std::cout << "CUBICSPLINE morph: exact motion, measured deviation " << worst << "\n";
}

// Stillness and breakpoints of an exact motion come from its tracks: a CUBICSPLINE track that holds one
// value with zero tangents between its last two keys is still there, and moves where the spline does.
TEST(GltfLoader, ExactMotionIsStillWhereItsTracksHold) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int node = addNode(w, {{"name", "settle"}, {"mesh", mesh}});
    setScene(w, {node});
    // Keys at 0, 1, 2 s: from the origin to (1, 0, 0), then held there (zero tangents into and out of it).
    const std::vector<float> tr = {0, 0, 0, 0, 0, 0, 1, 0, 0, /**/ 0, 0, 0, 1, 0, 0, 0, 0, 0, /**/ 0, 0, 0, 1, 0, 0, 0, 0, 0};
    animate(w, node, "translation", "CUBICSPLINE", {0, 1, 2}, tr);
    const Object o = loadValid(w, "settle").objects.at(0);
    ASSERT_TRUE(o.motion);
    EXPECT_FALSE(isStatic(o, 5, 10));
    EXPECT_FALSE(isStatic(o, 20, 30));  // reaches into the moving first interval
    EXPECT_TRUE(isStatic(o, 24, 40));
    EXPECT_TRUE(isStatic(o, 50, 60));  // held after the last key
    EXPECT_TRUE(isStatic(o, -10, 0));  // held before the first
    std::vector<double> breaks;
    addMotionKeyTimes(o, 0, 48, breaks);
    EXPECT_EQ(breaks, std::vector<double>{24.0});  // strictly inside (0, 48)
}

TEST(GltfLoader, CameraAnimatedLikeSpinPanGivesTheYamlCameraPoses) {
    // configs/table1/spin_pan.yaml's keys, the second at 12 frames (0.5 s at 24 fps, exact in float).
    Camera yaml;
    yaml.vfov_degrees = 40;
    yaml.keys = {{0, {0, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {12, {0, 0, 0}, {0, 0.1, 1}, {0.1, 1, 0}}};
    std::vector<float> rot;
    for (const CameraKey& k : yaml.keys) {
        // The camera looks down its node's -Z with +Y up.
        const glm::dvec3 z = -glm::normalize(k.view);
        const glm::dvec3 y = glm::normalize(k.up - glm::dot(k.up, z) * z);
        const glm::dquat q = glm::quat_cast(glm::dmat3(glm::cross(y, z), y, z));
        rot.insert(rot.end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
    }
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    w.doc()["cameras"] = json::array({{{"type", "perspective"}, {"name", "lens"},
                                       {"perspective", {{"yfov", 40 * M_PI / 180}, {"znear", 0.1}, {"aspectRatio", 16.0 / 9}}}}});
    const int cam = addNode(w, {{"name", "shotcam"}, {"camera", 0}});
    const int wall = addNode(w, {{"name", "wall"}, {"mesh", mesh}, {"translation", {0, 0, 10}}});
    setScene(w, {cam, wall});
    animate(w, cam, "rotation", "LINEAR", {0, 0.5}, rot);
    const GltfScene s = loadValid(w, "spin_pan_camera");
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_NEAR(s.camera->vfov_degrees, 40.0, 1e-5);
    EXPECT_EQ(s.camera->keys.size(), 2u);  // exact: one animated node, LINEAR
    for (const double t : {0.0, 3.0, 6.0, 9.5, 12.0}) {
        const CameraFrame a = evalCamera(yaml, t);
        const CameraFrame b = evalCamera(*s.camera, t);
        // 1e-6: the glTF rotation is stored as float (about 6e-8 relative per component).
        EXPECT_LT(glm::length(a.position - b.position), 1e-6) << t;
        EXPECT_LT(glm::length(a.e1 - b.e1), 1e-6) << t;
        EXPECT_LT(glm::length(a.e2 - b.e2), 1e-6) << t;
        EXPECT_LT(glm::length(a.e3 - b.e3), 1e-6) << t;
    }
}

// The boom: a camera (5 units out unless `cam` says otherwise) on a node that swings 90 degrees about +Y
// over a second.
GltfWriter boomCamera(std::vector<float>& swing, json cam = {{"translation", {0, 0, 5}}}) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    w.doc()["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}}});
    cam["name"] = "boom_cam";
    cam["camera"] = 0;
    const int cam_node = addNode(w, cam);
    const int boom = addNode(w, {{"name", "boom"}, {"children", {cam_node}}});
    setScene(w, {boom, addNode(w, {{"mesh", mesh}, {"translation", {0, 0, -10}}})});
    swing = quat(0, {0, 1, 0});
    const std::vector<float> swung = quat(90, {0, 1, 0});
    swing.insert(swing.end(), swung.begin(), swung.end());
    animate(w, boom, "rotation", "LINEAR", {0, 1}, swing);
    return w;
}

// The glTF camera of a world matrix, computed here: at the translation, looking down -Z, +Y made
// orthogonal to it.
CameraFrame frameOfMatrix(const glm::dmat4& m) {
    CameraFrame f;
    f.position = glm::dvec3(m[3]);
    f.e3 = -glm::normalize(glm::dvec3(m[2]));
    const glm::dvec3 y(m[1]);
    f.e1 = glm::normalize(y - glm::dot(y, f.e3) * f.e3);
    f.e2 = glm::cross(f.e3, f.e1);
    return f;
}

double frameDistance(const CameraFrame& a, const CameraFrame& b) {
    return std::max({glm::length(a.position - b.position), glm::length(a.e1 - b.e1), glm::length(a.e2 - b.e2),
                     glm::length(a.e3 - b.e3)});
}

// The camera's worst deviation from truth(t) at seeded times, through evalCamera and CameraPath (which
// must agree bit for bit).
double worstCameraDeviation(const Camera& camera, const std::function<glm::dmat4(double)>& truth,
                            const std::vector<double>& times) {
    const CameraPath path(camera);
    double worst = 0.0;
    for (const double t : times) {
        const CameraFrame f = evalCamera(camera, t);
        const CameraFrame p = path.at(t);
        EXPECT_EQ(std::memcmp(&f, &p, sizeof f), 0) << t;
        worst = std::max(worst, frameDistance(f, frameOfMatrix(truth(t))));
    }
    return worst;
}

// The worst distance of the rates MotionSnapshot takes from the camera (what propagation reads) from
// central differences of truth(t)'s camera, h = 1e-4 frames: the difference is truncation, falling as
// h^2 (measured 1.6e-9 at h = 1e-3, 2e-11 at 1e-4), and rounding (1e-16 / h of quantities of a few
// units, 3e-12) stays below it; callers allow 1e-9.
double worstRateDeviation(const Camera& camera, const std::function<glm::dmat4(double)>& truth,
                          const std::vector<double>& times) {
    Scene scene;
    scene.camera = camera;
    const Projection projection(64, 64, 40.0);
    constexpr double h = 1e-4;
    double worst = 0.0;
    for (const double t : times) {
        const MotionSnapshot snap(scene, projection, t);
        const CameraFrame f = frameOfMatrix(truth(t)), a = frameOfMatrix(truth(t - h)), b = frameOfMatrix(truth(t + h));
        const glm::dvec3 velocity = (b.position - a.position) / (2 * h);
        const glm::dvec3 omega = 0.5 * (glm::cross(f.e1, b.e1 - a.e1) + glm::cross(f.e2, b.e2 - a.e2) +
                                        glm::cross(f.e3, b.e3 - a.e3)) / (2 * h);
        worst = std::max({worst, glm::length(snap.camera_velocity - velocity),
                          glm::length(snap.camera_angular_velocity - omega)});
    }
    return worst;
}

TEST(GltfLoader, CameraUnderAnAnimatedParentIsFollowedExactly) {
    std::vector<float> swing;
    const GltfScene s = loadValid(boomCamera(swing), "boom_camera");
    ASSERT_TRUE(s.camera.has_value());
    ASSERT_TRUE(s.camera->motion);  // a static offset under a turning node: no key path is exact
    ASSERT_EQ(s.camera->keys.size(), 2u);  // its poses at the key times 0 and 24, for reports
    EXPECT_EQ(s.camera->keys[1].time, 24.0);
    const auto truth = [&](double t) {
        return trs({}, glm::slerp(toQuat(swing), toQuat(swing, 4), std::clamp(t / 24, 0.0, 1.0)), glm::dvec3(1)) *
               trs({0, 0, 5}, glm::dquat(1, 0, 0, 0), glm::dvec3(1));
    };
    // 1e-12: a product of two matrices and a normalisation, in double, against the same in the test.
    const double worst = worstCameraDeviation(*s.camera, truth, seededTimes(-2, 26, 2000, 17));
    EXPECT_LT(worst, 1e-12);
    std::cout << "boom camera: measured deviation " << worst << "\n";
}

TEST(GltfLoader, BoomCameraRatesStillnessAndTurn) {
    std::vector<float> swing;
    const GltfScene gs = loadValid(boomCamera(swing), "boom_camera_rates");
    Scene scene;
    scene.camera = *gs.camera;
    scene.objects = gs.objects;
    // The boom turns about +Y at a constant rate through the angle of its stored (float) key.
    const glm::dquat end = toQuat(swing, 4);
    const double angle = 2.0 * std::atan2(glm::length(glm::dvec3(end.x, end.y, end.z)), end.w);
    const glm::dvec3 omega(0.0, angle / 24.0, 0.0);
    const Projection projection(64, 64, 40.0);
    for (const double t : seededTimes(0, 23.9, 50, 5)) {
        const MotionSnapshot snap(scene, projection, t);
        // Rigid turn about the origin: d rc / dt = omega x rc. 1e-14: rounding of a few products.
        EXPECT_LT(glm::length(snap.camera_angular_velocity - omega), 1e-14) << t;
        EXPECT_LT(glm::length(snap.camera_velocity - glm::cross(omega, snap.camera.position)), 1e-14) << t;
    }
    const FrameMotion whole(scene, 0, 24);
    EXPECT_FALSE(whole.shutter().camera_still);
    EXPECT_FALSE(whole.shutter().eye_still);
    // A turn about a fixed axis: the chords add up to the angle. 1e-12: acos near its ends.
    EXPECT_NEAR(whole.turns(0, 24).camera, angle, 1e-12);
    EXPECT_NEAR(FrameMotion(scene, 6, 18).turns(6, 18).camera, angle / 2, 1e-12);
    const FrameMotion after(scene, 30, 40);
    EXPECT_TRUE(after.shutter().camera_still);
    EXPECT_EQ(after.turns(30, 40).camera, 0.0);
}

TEST(GltfLoader, CameraAtTheBoomPivotKeepsItsEyeStill) {
    std::vector<float> swing;
    // Tilted on the boom's axis: a static tail without an offset.
    const std::vector<float> tilt = quat(10, {1, 0, 0});
    const GltfScene gs = loadValid(boomCamera(swing, {{"rotation", tilt}}), "boom_camera_pivot");
    Scene scene;
    scene.camera = *gs.camera;
    scene.objects = gs.objects;
    ASSERT_TRUE(scene.camera.motion);  // a tail under the animated node: no key path is exact
    const FrameMotion motion(scene, 0, 24);
    EXPECT_FALSE(motion.shutter().camera_still);
    EXPECT_TRUE(motion.shutter().eye_still);
}

// glTF 2.0 Appendix C, written out here: the cubic Hermite spline of key k at u, tangents scaled by
// the key interval dt; keys of `width` numbers stored as (in-tangent, value, out-tangent).
std::vector<double> hermite(const std::vector<float>& v, std::size_t width, std::size_t k, double u, double dt) {
    const auto at = [&](std::size_t key, std::size_t part, std::size_t i) { return double(v[(3 * key + part) * width + i]); };
    std::vector<double> out(width);
    for (std::size_t i = 0; i < width; ++i)
        out[i] = (2 * u * u * u - 3 * u * u + 1) * at(k, 1, i) + dt * (u * u * u - 2 * u * u + u) * at(k, 2, i) +
                 (-2 * u * u * u + 3 * u * u) * at(k + 1, 1, i) + dt * (u * u * u - u * u) * at(k + 1, 0, i);
    return out;
}

TEST(GltfLoader, CubicSplineCameraIsFollowedExactly) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    w.doc()["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}}});
    const int cam = addNode(w, {{"name", "crane"}, {"camera", 0}});
    setScene(w, {cam, addNode(w, {{"mesh", mesh}, {"translation", {0, 0, -10}}})});
    const std::vector<float> times = {0, 0.5, 1};
    const std::vector<float> moves = {0, 0, 0, /**/ 0, 0, 0, /**/ 1, 0, 2, /**/ -1, 3, 0, /**/ 1, 0.5, 0, /**/ 2, 1, -1,
                                      0, 0, 1, /**/ 2, 0, 1, /**/ 0, 0, 0};
    std::vector<float> turns;
    const std::vector<std::vector<float>> keys = {quat(0, {0, 1, 0}), quat(30, {0, 1, 0}), quat(60, {1, 1, 0})};
    const std::vector<std::vector<float>> tangents = {{0, 0.2f, 0, 0}, {0.1f, 0.3f, -0.1f, 0}, {0, 0, 0.2f, 0}};
    for (std::size_t k = 0; k < 3; ++k) {
        turns.insert(turns.end(), tangents[k].begin(), tangents[k].end());
        turns.insert(turns.end(), keys[k].begin(), keys[k].end());
        turns.insert(turns.end(), tangents[(k + 1) % 3].begin(), tangents[(k + 1) % 3].end());
    }
    animate(w, cam, "translation", "CUBICSPLINE", times, moves);
    animate(w, cam, "rotation", "CUBICSPLINE", times, turns);
    const GltfScene s = loadValid(w, "cubic_camera");
    ASSERT_TRUE(s.camera.has_value());
    ASSERT_TRUE(s.camera->motion);
    EXPECT_EQ(s.camera->keys.size(), 3u);
    const auto truth = [&](double t) {
        const double seconds = std::clamp(t / 24.0, 0.0, 1.0);
        const std::size_t k = seconds < 0.5 ? 0 : 1;
        const double u = k == 1 && seconds == 1.0 ? 1.0 : (seconds - times[k]) / 0.5;
        const std::vector<double> p = hermite(moves, 3, k, u, 0.5);
        const std::vector<double> q = hermite(turns, 4, k, u, 0.5);
        return trs({p[0], p[1], p[2]}, glm::normalize(glm::dquat(q[3], q[0], q[1], q[2])), glm::dvec3(1));
    };
    // 1e-12: the same polynomials and one normalisation, summed in another order.
    const double worst = worstCameraDeviation(*s.camera, truth, seededTimes(-2, 26, 2000, 23));
    EXPECT_LT(worst, 1e-12);
    std::cout << "CUBICSPLINE camera: measured deviation " << worst << "\n";
    std::vector<double> inside = seededTimes(0.5, 11.5, 100, 31);  // away from the keys' kinks
    for (const double t : seededTimes(12.5, 23.5, 100, 37)) inside.push_back(t);
    const double rates = worstRateDeviation(*s.camera, truth, inside);
    EXPECT_LT(rates, 1e-9);
    std::cout << "CUBICSPLINE camera: rates against central differences " << rates << "\n";
}

TEST(GltfLoader, CameraUnderAShearingParentLooksDownItsMinusZColumn) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    w.doc()["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}}});
    const int cam = addNode(w, {{"name", "cam"}, {"camera", 0}, {"translation", {1, 2, 3}}});
    const std::vector<float> tilt = quat(30, {0, 0, 1});
    // A non-uniform scale above a turning child: the camera's world matrix has shear.
    const int rig = addNode(w, {{"name", "rig"}, {"rotation", tilt}, {"scale", {1, 2, 0.5}}, {"children", {cam}}});
    setScene(w, {rig, addNode(w, {{"mesh", mesh}, {"translation", {0, 0, -10}}})});
    std::vector<float> roll = quat(0, {1, 0, 0});
    const std::vector<float> rolled = quat(45, {1, 0, 0});
    roll.insert(roll.end(), rolled.begin(), rolled.end());
    animate(w, cam, "rotation", "LINEAR", {0, 1}, roll);
    const GltfScene s = loadValid(w, "sheared_camera");
    ASSERT_TRUE(s.camera.has_value());
    ASSERT_TRUE(s.camera->motion);
    const glm::dmat4 parent = trs({}, toQuat(tilt), {1, 2, 0.5});
    const auto truth = [&](double t) {
        const glm::dquat r = glm::slerp(toQuat(roll), toQuat(roll, 4), std::clamp(t / 24, 0.0, 1.0));
        return parent * trs({1, 2, 3}, r, glm::dvec3(1));
    };
    // The matrix really is sheared somewhere in the shot, or this test shows nothing.
    const glm::dmat4 mid = truth(12);
    EXPECT_GT(std::abs(glm::dot(glm::normalize(glm::dvec3(mid[1])), glm::normalize(glm::dvec3(mid[2])))), 0.1);
    // 1e-12: as for the boom.
    const double worst = worstCameraDeviation(*s.camera, truth, seededTimes(-2, 26, 2000, 29));
    EXPECT_LT(worst, 1e-12);
    std::cout << "sheared camera: measured deviation " << worst << "\n";
    const double rates = worstRateDeviation(*s.camera, truth, seededTimes(0.5, 23.5, 200, 41));
    EXPECT_LT(rates, 1e-9);
    std::cout << "sheared camera: rates against central differences " << rates << "\n";
}

TEST(GltfLoader, CameraWithMoreKeysThanAllowedIsFollowedExactly) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    w.doc()["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}}});
    const int cam = addNode(w, {{"name", "dolly"}, {"camera", 0}});
    setScene(w, {cam, addNode(w, {{"mesh", mesh}, {"translation", {0, 0, -10}}})});
    const std::vector<float> times = {0, 0.25, 0.5, 0.75, 1, 1.25};
    const std::vector<float> path = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 2, 3, 0, 2};
    animate(w, cam, "translation", "LINEAR", times, path);
    GltfRequest r = request();
    r.max_transform_keys = 4;
    const GltfScene s = loadValid(w, "many_key_camera", r);
    ASSERT_TRUE(s.camera.has_value());
    ASSERT_TRUE(s.camera->motion);  // six key times, four allowed
    EXPECT_EQ(s.camera->keys.size(), 6u);
    const auto truth = [&](double t) {
        const double seconds = std::clamp(t / 24.0, 0.0, 1.25);
        const std::size_t k = std::min<std::size_t>(4, static_cast<std::size_t>(seconds / 0.25));
        const double u = (seconds - times[k]) / 0.25;
        glm::dvec3 p;
        for (int i = 0; i < 3; ++i) p[i] = (1 - u) * path[3 * k + i] + u * path[3 * (k + 1) + i];
        return trs(p, glm::dquat(1, 0, 0, 0), glm::dvec3(1));
    };
    // 1e-12: a lerp, computed here with another formula.
    EXPECT_LT(worstCameraDeviation(*s.camera, truth, seededTimes(-2, 32, 500, 43)), 1e-12);
}

TEST(GltfLoader, CameraWhoseViewCollapsesIsRefusedAtItsNode) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    w.doc()["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}}});
    const int cam = addNode(w, {{"name", "cam"}, {"camera", 0}, {"translation", {0, 0, 1}}});
    const int rig = addNode(w, {{"name", "rig"}, {"children", {cam}}});
    setScene(w, {rig, addNode(w, {{"mesh", mesh}, {"translation", {0, 0, -10}}})});
    // The rig's z scale reaches 0 at 1 s (frame 24): the camera's -Z column vanishes there.
    animate(w, rig, "scale", "LINEAR", {0, 1}, {1, 1, 1, 1, 1, 0});
    const auto file = std::filesystem::path(::testing::TempDir()) / "collapsing_camera.gltf";
    w.writeGltf(file);
    try {
        loadGltfScene(file, request());
        ADD_FAILURE() << "a camera without a view direction loaded";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_NE(e.message().find("/nodes/" + std::to_string(cam) + ": at frame 24: camera view direction is zero"),
                  std::string::npos)
            << e.what();
    }
}

TEST(GltfLoader, MorphWeightsAreExactDeformationKeys) {
    GltfWriter w;
    std::vector<float> p;
    for (const glm::dvec3& v : kTetra) p.insert(p.end(), {float(v.x), float(v.y), float(v.z)});
    const int pos = w.addFloats(p, "VEC3", 34962);
    const int idx = w.addIndices({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, 5123);
    const int d0 = w.addFloats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1}, "VEC3", 34962);  // vertex 3 up
    const int d1 = w.addFloats({0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 34962);  // vertex 1 out
    w.doc()["meshes"].push_back({{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", idx},
                                                              {"targets", json::array({{{"POSITION", d0}}, {{"POSITION", d1}}})}}})},
                                 {"weights", {0, 0}}});
    const int node = addNode(w, {{"name", "blob"}, {"mesh", 0}});
    setScene(w, {node});
    animate(w, node, "weights", "LINEAR", {0, 1, 2}, {0, 0, 1, 0, 1, 1});
    const Object o = loadValid(w, "morph").objects.at(0);
    ASSERT_EQ(o.deformation.size(), 3u);
    // 1.5 s = 36 frames: weights (1, 0.5) by hand.
    EXPECT_LT(glm::length(evalVertex(o, 3, 36) - glm::dvec3(0, 0, 2)), 1e-12);
    EXPECT_LT(glm::length(evalVertex(o, 1, 36) - glm::dvec3(1.5, 0, 0)), 1e-12);
    EXPECT_LT(glm::length(evalVertex(o, 1, 6) - glm::dvec3(1, 0, 0)), 1e-12);
    EXPECT_LT(glm::length(evalVertex(o, 3, 6) - glm::dvec3(0, 0, 1.25)), 1e-12);
}

TEST(GltfLoader, SkinIsFollowedExactly) {
    GltfWriter w;
    // A bar of three rows (y = 0, 1, 2), bound to a hip at the origin and a knee at y = 1 that bends.
    const int pos = w.addFloats({-0.1f, 0, 0, 0.1f, 0, 0, -0.1f, 1, 0, 0.1f, 1, 0, -0.1f, 2, 0, 0.1f, 2, 0}, "VEC3", 34962);
    const int idx = w.addIndices({0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4}, 5123);
    // Joint 0 the hip, 1 the knee; components of zero weight name joint 0 (the validator asks for it).
    const std::vector<std::uint32_t> joint_ids = {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    const int joints = w.addUnsigned(joint_ids, 5121, "VEC4");
    const std::vector<float> weights = {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    const int wts = w.addFloats(weights, "VEC4", 34962);
    const int ibm = w.addFloats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, /**/ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1}, "MAT4");
    w.doc()["meshes"].push_back({{"primitives", json::array({{{"attributes", {{"POSITION", pos}, {"JOINTS_0", joints}, {"WEIGHTS_0", wts}}},
                                                              {"indices", idx}}})}});
    addNode(w, {{"name", "leg"}, {"mesh", 0}, {"skin", 0}});
    const int hip = addNode(w, {{"name", "hip"}, {"children", {2}}});
    const int knee = addNode(w, {{"name", "knee"}, {"translation", {0, 1, 0}}});
    w.doc()["skins"] = json::array({{{"joints", {hip, knee}}, {"inverseBindMatrices", ibm}}});
    setScene(w, {0, hip});
    std::vector<float> bend = quat(0, {0, 0, 1});
    const std::vector<float> bent = quat(90, {0, 0, 1});
    bend.insert(bend.end(), bent.begin(), bent.end());
    animate(w, knee, "rotation", "LINEAR", {0, 1}, bend);
    GltfRequest r = request();
    r.fps = 1.0;  // 1 s = frame 0's whole shutter
    const Object o = loadValid(w, "skin", r).objects.at(0);
    EXPECT_TRUE(o.transform.empty());
    EXPECT_TRUE(o.deformation.empty());
    ASSERT_TRUE(o.motion);
    // Hand value at the end: the tip (0.1, 2) turned 90 degrees about the knee (0, 1): (-1, 1.1); 1e-7 for
    // the float-stored quaternion and positions.
    EXPECT_LT(glm::length(evalVertex(o, 5, 1.0) - glm::dvec3(-1, 1.1, 0)), 1e-7);
    // The float-stored rest positions, as the file holds them.
    const std::vector<glm::dvec3> rest = {{-0.1f, 0, 0}, {0.1f, 0, 0}, {-0.1f, 1, 0}, {0.1f, 1, 0}, {-0.1f, 2, 0}, {0.1f, 2, 0}};
    double worst = 0.0;
    for (const double t : seededTimes(0, 1, 4000, 13)) {
        const glm::dquat q = glm::slerp(toQuat(bend), toQuat(bend, 4), t);
        const glm::dmat4 knee_m = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 1, 0)) * glm::mat4_cast(q) *
                                  glm::translate(glm::dmat4(1.0), glm::dvec3(0, -1, 0));
        for (std::uint32_t v = 0; v < rest.size(); ++v) {
            glm::dvec3 truth(0.0);
            for (std::uint32_t k = 0; k < 4; ++k)
                truth += double(weights[4 * v + k]) * (joint_ids[4 * v + k] == 1 ? apply(knee_m, rest[v]) : rest[v]);
            worst = std::max(worst, glm::length(evalVertex(o, v, t) - truth));
        }
    }
    // 1e-12 of a bar 2 long: the same skin sum, rounded in another order.
    EXPECT_LT(worst, 1e-12);
    std::cout << "skin: exact motion, measured deviation " << worst << "\n";
}

TEST(GltfLoader, GlbAndBinBufferLoadLikeTheDataUri) {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int node = addNode(w, {{"name", "a"}, {"mesh", mesh}, {"translation", {1, 2, 3}}});
    const int twin = addNode(w, {{"name", "a"}, {"mesh", mesh}});
    setScene(w, {node, twin});
    const GltfScene uri = loadValid(w, "names");
    const auto dir = testing::validatedAssetDir();
    w.writeGlb(dir / "names_glb.glb");
    w.writeGltfWithBin(dir / "names_bin.gltf");
    for (const char* f : {"names_glb.glb", "names_bin.gltf"}) {
        const GltfScene s = loadGltfScene(dir / f, request());
        ASSERT_EQ(s.objects.size(), 2u) << f;
        EXPECT_EQ(s.objects[0].mesh.positions, uri.objects[0].mesh.positions) << f;
    }
    EXPECT_EQ(loadGltfScene(dir / "names_bin.gltf", request()).buffer_files,
              std::vector<std::filesystem::path>{dir / "names_bin.bin"});
    EXPECT_TRUE(uri.buffer_files.empty());
    // Two nodes of one name: the second gets "#2".
    EXPECT_EQ(uri.objects[0].name, "a");
    EXPECT_EQ(uri.objects[1].name, "a#2");
}

TEST(GltfLoader, PrimitiveModesAreReadOrReported) {
    GltfWriter w;
    std::vector<float> p;
    for (const glm::dvec3& v : kTetra) p.insert(p.end(), {float(v.x), float(v.y), float(v.z)});
    const int pos = w.addFloats(p, "VEC3", 34962);
    // Not indexed: vertices 0 1 2 as one triangle needs exactly three; a strip over all four gives two.
    const int tri = w.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 34962);
    const int line_idx = w.addIndices({0, 1}, 5123);
    w.doc()["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    w.doc()["materials"] = json::array({{{"emissiveFactor", {1, 1, 1}},
                                         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 2}}}}}}});
    w.doc()["meshes"].push_back({{"primitives", json::array({{{"attributes", {{"POSITION", tri}}}, {"material", 0}},
                                                             {{"attributes", {{"POSITION", pos}}}, {"mode", 5}},
                                                             {{"attributes", {{"POSITION", pos}}}, {"indices", line_idx}, {"mode", 1}}})}});
    setScene(w, {addNode(w, {{"name", "modes"}, {"mesh", 0}})});
    const GltfScene s = loadValid(w, "modes");
    ASSERT_EQ(s.objects.size(), 2u);
    EXPECT_EQ(s.objects[0].name, "modes/0");
    EXPECT_EQ(s.objects[0].mesh.triangles, (std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}}));
    EXPECT_EQ(s.objects[1].name, "modes/1");
    // TRIANGLE_STRIP: every other triangle flipped so that all keep the first one's winding.
    EXPECT_EQ(s.objects[1].mesh.triangles, (std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {2, 1, 3}}));
    const auto has = [&](const std::string& what) {
        return std::any_of(s.warnings.begin(), s.warnings.end(), [&](const std::string& m) { return m.find(what) != std::string::npos; });
    };
    EXPECT_TRUE(has("points and lines are skipped (/meshes/0/primitives/2"));
    EXPECT_FALSE(has("emission"));
}

// NORMAL and TEXCOORD_0 become corner attributes (normals by the inverse transpose of the folded node
// matrix, so they stay normal to the scaled surface), baseColorTexture names its image file beside the
// .gltf, KHR_texture_transform is applied to the UVs, and a texCoord other than 0 is refused.
TEST(GltfLoader, NormalsUvsAndBaseColorTextureAreRead) {
    const auto folder = testing::validatedAssetDir();
    testing::writeRgb8Png(folder / "textured_quad.png", 2, 2, {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255});
    const auto build = [&](int tex_coord, bool transform) {
        GltfWriter w;
        const int pos = w.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 34962);
        // Unit normals tilted 45 degrees in x and y; UVs the image's corners.
        const float h = static_cast<float>(std::sqrt(0.5));
        const int normal = w.addFloats({h, 0, -h, h, 0, -h, 0, h, -h, 0, h, -h}, "VEC3", 34962);
        const int uv = w.addFloats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 34962);
        const int idx = w.addIndices({0, 2, 1, 0, 3, 2}, 5123);
        json info = {{"index", 0}};
        if (tex_coord != 0) info["texCoord"] = tex_coord;
        if (transform) {
            info["extensions"] = {{"KHR_texture_transform", {{"offset", {0.25, 0.5}}, {"rotation", kHalfPi}, {"scale", {2, 3}}}}};
            w.doc()["extensionsUsed"] = {"KHR_texture_transform"};
        }
        w.doc()["images"] = json::array({{{"uri", "textured_quad.png"}}});
        w.doc()["textures"] = json::array({{{"source", 0}}});
        w.doc()["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", info},
                                                                       {"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}}});
        w.doc()["meshes"].push_back(
            {{"primitives", json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", normal}, {"TEXCOORD_0", uv}}},
                                          {"indices", idx},
                                          {"material", 0}}})}});
        setScene(w, {addNode(w, {{"name", "quad"}, {"mesh", 0}, {"scale", {2, 1, 1}}})});
        return w;
    };
    const GltfScene s = loadValid(build(0, true), "textured_quad");
    ASSERT_EQ(s.objects.size(), 1u);
    const Mesh& m = s.objects[0].mesh;
    ASSERT_EQ(m.corner_normals.size(), 6u);
    ASSERT_EQ(m.corner_uvs.size(), 6u);
    // Corner 1 is vertex 2 (UV (1, 0), normal (0, h, -h)); corner 4 is vertex 3 (UV (0, 0)). The transform
    // by hand, per the extension's T R S: scale (u, v) -> (2u, 3v), rotate a quarter turn with R = [0 1;
    // -1 0] -> (3v, -2u), offset -> (3v + 0.25, -2u + 0.5). 1e-12: cos(pi/2) is 6e-17, not 0.
    const auto near = [](glm::dvec2 a, glm::dvec2 b) { return glm::length(a - b) < 1e-12; };
    EXPECT_PRED2(near, m.corner_uvs[1], glm::dvec2(0.25, -1.5));
    EXPECT_PRED2(near, m.corner_uvs[4], glm::dvec2(0.25, 0.5));
    EXPECT_PRED2(near, m.corner_uvs[0], glm::dvec2(3.25, 0.5));
    const GltfScene plain = loadValid(build(0, false), "textured_quad_plain");
    EXPECT_EQ(plain.objects.at(0).mesh.corner_uvs[1], glm::dvec2(1, 0));
    // Scale (2, 1, 1): the inverse transpose divides x by 2. The normal (h, 0, -h) becomes (h/2, 0, -h); it
    // must stay perpendicular to the scaled surface's tangents. 1e-7: float attributes.
    const glm::dvec3 n0 = glm::normalize(m.corner_normals[0]);
    EXPECT_LT(glm::length(n0 - glm::normalize(glm::dvec3(0.5, 0, -1))), 1e-7);
    const glm::dvec3 n1 = glm::normalize(m.corner_normals[1]);
    EXPECT_LT(glm::length(n1 - glm::normalize(glm::dvec3(0, 1, -1))), 1e-7);
    const Material& mat = s.materials[static_cast<std::size_t>(s.objects[0].material)];
    EXPECT_EQ(mat.base_color, glm::dvec3(0.5));
    EXPECT_EQ(std::filesystem::path(mat.image.file), folder / "textured_quad.png");
    EXPECT_TRUE(s.warnings.empty());

    // An emissive texture transformed otherwise than the base colour's: one set of UVs cannot serve both.
    GltfWriter two = build(0, true);
    two.doc()["materials"][0]["emissiveFactor"] = {1, 1, 1};
    two.doc()["materials"][0]["emissiveTexture"] = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {2, 2}}}}}}};
    const auto two_file = folder / "two_transforms.gltf";  // beside its image; valid glTF, refused here
    two.writeGltf(two_file);
    try {
        loadGltfScene(two_file, request());
        ADD_FAILURE() << "two transforms loaded";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_NE(e.message().find("/materials/0/emissiveTexture/extensions/KHR_texture_transform: differs from the "
                                   "baseColorTexture's"),
                  std::string::npos)
            << e.what();
    }

    const auto file = std::filesystem::path(::testing::TempDir()) / "texcoord1.gltf";
    build(1, false).writeGltf(file);
    try {
        loadGltfScene(file, request());
        ADD_FAILURE() << "texCoord 1 loaded";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_NE(e.message().find("/materials/0/pbrMetallicRoughness/baseColorTexture: texCoord 1 is not supported"),
                  std::string::npos)
            << e.what();
    }
}

// Blender 3.4's export of a textured mesh without a UV map: the material names a baseColorTexture (or an
// emissiveTexture) but the primitive has POSITION and NORMAL only. Refused at the primitive's material,
// where the Khronos validator reports MESH_PRIMITIVE_TOO_FEW_TEXCOORDS; with TEXCOORD_0 it loads.
TEST(GltfLoader, TextureOnAPrimitiveWithoutTexcoordsIsRefused) {
    const auto dir = std::filesystem::path(::testing::TempDir()) / "clipblur_gltf_no_uvs";
    std::filesystem::create_directories(dir);
    testing::writeRgb8Png(dir / "checker.png", 2, 1, {255, 255, 255, 0, 0, 0});
    const auto build = [](const json& material, bool uvs) {
        GltfWriter w;
        const int pos = w.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0}, "VEC3", 34962);
        const int normal = w.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 34962);
        json attributes = {{"POSITION", pos}, {"NORMAL", normal}};
        if (uvs) attributes["TEXCOORD_0"] = w.addFloats({0, 0, 1, 0, 1, 1}, "VEC2", 34962);
        w.doc()["images"] = json::array({{{"uri", "checker.png"}}});
        w.doc()["textures"] = json::array({{{"source", 0}}});
        // A plain material first, so the textured one's index (1) shows in the message.
        w.doc()["materials"] = json::array({{{"name", "plain"}}, material});
        w.doc()["meshes"].push_back(
            {{"primitives", json::array({{{"attributes", attributes}, {"indices", w.addIndices({0, 1, 2}, 5123)},
                                          {"material", 1}}})}});
        setScene(w, {addNode(w, {{"name", "floor"}, {"mesh", 0}})});
        return w;
    };
    const json base = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}};
    const json glow = {{"emissiveFactor", {1, 1, 1}}, {"emissiveTexture", {{"index", 0}}}};
    for (const auto& [name, material, texture] :
         {std::tuple{"base", base, "baseColorTexture"}, std::tuple{"glow", glow, "emissiveTexture"}}) {
        build(material, true).writeGltf(dir / (std::string(name) + "_uvs.gltf"));
        EXPECT_EQ(loadGltfScene(dir / (std::string(name) + "_uvs.gltf"), request()).objects.size(), 1u) << name;
        build(material, false).writeGltf(dir / (std::string(name) + ".gltf"));
        try {
            loadGltfScene(dir / (std::string(name) + ".gltf"), request());
            ADD_FAILURE() << name << " loaded";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::Scene);
            EXPECT_NE(std::string(e.what()).find(std::string(name) + ".gltf: /meshes/0/primitives/0/material: material 1's " +
                                                 texture + " reads TEXCOORD_0, which the primitive lacks"),
                      std::string::npos)
                << e.what();
        }
    }
}

// KHR_materials_unlit makes a material unlit (its base colour and texture kept, its emission ignored with
// a warning); emissiveFactor times KHR_materials_emissive_strength's emissiveStrength (1 when absent)
// is the emission, emissiveTexture its image beside the .gltf. Both extensions may be required.
TEST(GltfLoader, UnlitAndEmissiveMaterialsAreRead) {
    const auto folder = testing::validatedAssetDir();
    testing::writeRgb8Png(folder / "emissive_glow.png", 2, 1, {255, 128, 0, 0, 64, 255});
    GltfWriter w;
    const int pos = w.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 34962);
    const int uv = w.addFloats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 34962);
    const int idx = w.addIndices({0, 2, 1, 0, 3, 2}, 5123);
    w.doc()["extensionsUsed"] = {"KHR_materials_unlit", "KHR_materials_emissive_strength"};
    w.doc()["extensionsRequired"] = {"KHR_materials_unlit", "KHR_materials_emissive_strength"};
    w.doc()["images"] = json::array({{{"uri", "emissive_glow.png"}}});
    w.doc()["textures"] = json::array({{{"source", 0}}});
    w.doc()["materials"] = json::array(
        {{{"name", "flat"},
          {"pbrMetallicRoughness", {{"baseColorFactor", {0.25, 0.5, 0.75, 1}}, {"baseColorTexture", {{"index", 0}}}}},
          {"extensions", {{"KHR_materials_unlit", json::object()}}}},
         {{"name", "lamp"},
          {"emissiveFactor", {1, 0.5, 0.25}},
          {"emissiveTexture", {{"index", 0}}},
          {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}},
         {{"name", "ember"}, {"emissiveFactor", {0.5, 0.125, 0}}},
         {{"name", "flat_glow"}, {"emissiveFactor", {1, 1, 1}}, {"extensions", {{"KHR_materials_unlit", json::object()}}}}});
    json primitives = json::array();
    for (int m = 0; m < 4; ++m)
        primitives.push_back({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"indices", idx}, {"material", m}});
    w.doc()["meshes"] = json::array({{{"primitives", primitives}}});
    setScene(w, {addNode(w, {{"name", "panel"}, {"mesh", 0}})});
    const GltfScene s = loadValid(w, "unlit_emissive");
    ASSERT_EQ(s.objects.size(), 4u);
    const auto material = [&](int object) { return s.materials.at(static_cast<std::size_t>(s.objects.at(object).material)); };
    EXPECT_EQ(material(0).model, ShadingModel::Unlit);
    EXPECT_EQ(material(0).base_color, glm::dvec3(0.25, 0.5, 0.75));
    EXPECT_EQ(std::filesystem::path(material(0).image.file), folder / "emissive_glow.png");
    EXPECT_EQ(material(0).emission, glm::dvec3(0.0));
    EXPECT_EQ(material(1).model, ShadingModel::Lit);
    EXPECT_EQ(material(1).emission, glm::dvec3(4, 2, 1));
    EXPECT_EQ(std::filesystem::path(material(1).emission_image.file), folder / "emissive_glow.png");
    EXPECT_TRUE(material(1).image.file.empty());
    EXPECT_EQ(material(2).emission, glm::dvec3(0.5, 0.125, 0));
    EXPECT_TRUE(material(2).emission_image.file.empty());
    EXPECT_EQ(material(3).model, ShadingModel::Unlit);
    EXPECT_EQ(material(3).emission, glm::dvec3(0.0));
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("emission of unlit materials is ignored (/materials/3"), std::string::npos) << s.warnings[0];
}

namespace {

struct BadCase {
    std::string name;
    std::function<void(GltfWriter&)> spoil;
    std::string expected;  // after "<name>.gltf: "
};

// Gives the first primitive a material, the file's only one.
void useMaterial(GltfWriter& w, json material) {
    w.doc()["materials"] = json::array({std::move(material)});
    w.doc()["meshes"][0]["primitives"][0]["material"] = 0;
}

// A valid animated scene, spoiled by each case.
GltfWriter goodScene() {
    GltfWriter w;
    const int mesh = addTetraMesh(w);
    const int node = addNode(w, {{"name", "n"}, {"mesh", mesh}});
    setScene(w, {node});
    animate(w, node, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0});
    return w;
}

}  // namespace

TEST(GltfLoader, BadFilesAreRefusedWithTheFileAndTheJsonPointer) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<BadCase> cases = {
        {"pos_vec4", [](GltfWriter& w) { w.doc()["accessors"][0]["type"] = "VEC4"; w.doc()["accessors"][0]["count"] = 3; },
         "/accessors/0: POSITION must be float VEC3"},
        {"index_range", [](GltfWriter& w) { w.doc()["meshes"][0]["primitives"][0]["indices"] = w.addIndices({0, 1, 7}, 5123); },
         "/accessors/4: index 7 is out of range: the primitive has 4 vertices"},
        {"index_float", [](GltfWriter& w) { w.doc()["accessors"][1]["componentType"] = 5126; w.doc()["accessors"][1]["count"] = 6; },
         "/accessors/1: indices must be unsigned byte, short or int SCALAR"},
        {"nan_position", [nan](GltfWriter& w) { w.doc()["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
                                                     w.addFloats({0, 0, 0, 1, 0, 0, nan, 1, 0, 0, 0, 1}, "VEC3"); },
         "/accessors/4: POSITION holds a non-finite number"},
        {"nan_key", [nan](GltfWriter& w) { w.doc()["animations"][0]["samplers"][0]["output"] = w.addFloats({0, 0, 0, nan, 0, 0}, "VEC3"); },
         "/accessors/4: an animation output holds a non-finite number"},
        {"key_order", [](GltfWriter& w) { w.doc()["animations"][0]["samplers"][0]["input"] = w.addFloats({1, 1}, "SCALAR"); },
         "/accessors/4: animation key times must increase strictly (key 1)"},
        {"key_count", [](GltfWriter& w) { w.doc()["animations"][0]["samplers"][0]["input"] = w.addFloats({0, 1, 2}, "SCALAR"); },
         "/accessors/3: an animation output needs 3 numbers per key time, 3 key times"},
        {"past_view", [](GltfWriter& w) { w.doc()["accessors"][0]["count"] = 40; }, "/accessors/0: count, byteOffset and stride reach beyond its bufferView"},
        {"no_view", [](GltfWriter& w) { w.doc()["accessors"][0]["bufferView"] = 99; }, "/accessors/0: bufferView 99 does not exist"},
        {"bad_node", [](GltfWriter& w) { w.doc()["scenes"][0]["nodes"] = {4}; }, "/scenes/0/nodes: node 4 does not exist"},
        {"joints_no_skin", [](GltfWriter& w) { w.doc()["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = 0; },
         "/meshes/0/primitives/0: JOINTS_0 without a skin on the node"},
        {"skin_range", [](GltfWriter& w) {
             w.doc()["nodes"][0]["skin"] = 0;
             w.doc()["skins"] = json::array({{{"joints", {0}}}});
             w.doc()["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = w.addUnsigned({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 3, 0, 0, 0}, 5121, "VEC4");
             w.doc()["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = w.addFloats(std::vector<float>(16, 0.25f), "VEC4");
         },
         "/accessors/4: joint 3 is out of range: the skin has 1"},
        {"deep", [](GltfWriter& w) {
             for (int i = 0; i < 1100; ++i) w.doc()["nodes"].push_back({{"children", {i + 1 < 1100 ? 2 + i : 0}}});
             w.doc()["scenes"][0]["nodes"] = {1};
         },
         "/nodes/1025: the hierarchy is deeper than 1024 levels"},
        {"draco", [](GltfWriter& w) {
             w.doc()["extensionsUsed"] = {"KHR_draco_mesh_compression"};
             w.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
         },
         "/extensionsRequired/0: extension KHR_draco_mesh_compression is not supported"},
        {"interp", [](GltfWriter& w) { w.doc()["animations"][0]["samplers"][0]["interpolation"] = "SMOOTH"; },
         "/animations/0: unknown interpolation 'SMOOTH'"},
        {"emissive_factor", [](GltfWriter& w) { useMaterial(w, {{"emissiveFactor", {0.5, 2, 0}}}); },
         "/materials/0/emissiveFactor: must be 3 numbers in [0, 1]"},
        {"emissive_strength", [](GltfWriter& w) {
             useMaterial(w, {{"emissiveFactor", {1, 1, 1}},
                             {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", -2}}}}}});
         },
         "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength: must be a number in [0, 1e8]"},
        {"emissive_strength_text", [](GltfWriter& w) {
             useMaterial(w, {{"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", "bright"}}}}}});
         },
         "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength: must be a number in [0, 1e8]"},
        {"emissive_texture", [](GltfWriter& w) { useMaterial(w, {{"emissiveFactor", {1, 1, 1}}, {"emissiveTexture", {{"index", 3}}}}); },
         "/materials/0/emissiveTexture: texture 3 does not exist"},
    };
    const auto dir = std::filesystem::path(::testing::TempDir()) / "clipblur_gltf_bad";
    std::filesystem::create_directories(dir);
    for (const BadCase& c : cases) {
        GltfWriter w = goodScene();
        c.spoil(w);
        const auto file = dir / (c.name + ".gltf");
        w.writeGltf(file);
        try {
            loadGltfScene(file, request());
            ADD_FAILURE() << c.name << " loaded";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::Scene) << c.name;
            const std::string expected = c.name + ".gltf: " + c.expected;
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << c.name << ": " << e.what();
            EXPECT_NE(std::string(e.what()).find("(glTF file of job.yaml:3:8)"), std::string::npos) << e.what();
        }
    }
    // A missing .bin buffer: tinygltf's own message, located at the file.
    GltfWriter w = goodScene();
    w.writeGltfWithBin(dir / "missing_bin.gltf");
    std::filesystem::remove(dir / "missing_bin.bin");
    try {
        loadGltfScene(dir / "missing_bin.gltf", request());
        ADD_FAILURE() << "missing_bin loaded";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_NE(std::string(e.what()).find("missing_bin.gltf: not a valid glTF file"), std::string::npos) << e.what();
    }
}

}  // namespace clipblur
