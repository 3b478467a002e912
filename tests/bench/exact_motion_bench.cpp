#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/gtc/quaternion.hpp>

#include "scene/exact_motion.h"
#include "scene/object_motion.h"
#include "scene/primitives.h"

namespace clipblur {

namespace {

// The cost of one vertex position at one time: transform keys (a lerp/slerp per call, then one
// transform per vertex) against an exact glTF motion (a car and wheel chain, LINEAR and CUBICSPLINE),
// and a two-joint skin. All on a sphere of about 4900 vertices, evaluated at a time between keys.
constexpr int kSegments = 100;

Track linearTrack(std::vector<double> values, std::size_t width, bool rotation) {
    Track t;
    t.width = width;
    t.rotation = rotation;
    t.times = {0.0, 24.0};
    t.values = std::move(values);
    return t;
}

Track cubicTrack() {
    Track t;
    t.interpolation = Interpolation::CubicSpline;
    t.times = {0.0, 24.0};
    t.values = {0, 0, 0, 0, 0, 0, 0.1, 0, 0, /**/ 0, 0.2, 0, 2, 1, 0, 0, 0, 0};
    return t;
}

struct Fixture {
    Object keyed, chain, skin;
    std::shared_ptr<AnimationStore> store = std::make_shared<AnimationStore>();

    Fixture() {
        keyed.mesh = makeSphere(1.0, kSegments);
        keyed.transform = {TransformKey{0.0, glm::dvec3(0), glm::dquat(1, 0, 0, 0), glm::dvec3(1)},
                           TransformKey{24.0, glm::dvec3(5, 0, 0), glm::angleAxis(1.0, glm::dvec3(0, 1, 0)), glm::dvec3(1)}};
        store->nodes.resize(3);
        const glm::dquat turned = glm::angleAxis(1.0, glm::dvec3(0, 1, 0));
        store->nodes[0].translation = &store->tracks.emplace_back(cubicTrack());
        store->nodes[0].rotation =
            &store->tracks.emplace_back(linearTrack({0, 0, 0, 1, turned.x, turned.y, turned.z, turned.w}, 4, true));
        store->nodes[1].rest.translate = glm::dvec3(1, 0.5, 0);
        store->nodes[1].rotation = &store->tracks.emplace_back(linearTrack({0, 0, 0, 1, 0, 0, 0.7071, 0.7071}, 4, true));
        chain.mesh = keyed.mesh;
        chain.motion = std::make_shared<ExactMotion>(store, ChainMotion{{&store->nodes[0], &store->nodes[1]}});
        skin.mesh = keyed.mesh;
        auto skinned = std::make_shared<ExactMotion>(store, ChainMotion{});
        SkinBinding binding;
        binding.joints = {ChainMotion{{&store->nodes[0]}}, ChainMotion{{&store->nodes[0], &store->nodes[1]}}};
        binding.inverse_bind = {glm::dmat4(1.0), glm::dmat4(1.0)};
        for (std::size_t v = 0; v < skin.mesh.positions.size(); ++v) {
            const double w = 0.5 + 0.5 * skin.mesh.positions[v].y;
            binding.joint_ids.insert(binding.joint_ids.end(), {0, 1, 0, 0});
            binding.weights.insert(binding.weights.end(), {w, 1.0 - w, 0.0, 0.0});
        }
        skinned->setSkin(std::move(binding));
        skin.motion = std::move(skinned);
    }
};

const Fixture& fixture() {
    static const Fixture f;
    return f;
}

void run(benchmark::State& state, const Object& object) {
    std::vector<glm::dvec3> out;
    double t = 7.3;
    for (auto _ : state) {
        evalVertices(object, t, out);
        benchmark::DoNotOptimize(out.data());
        t += 1e-6;
    }
    state.SetItemsProcessed(state.iterations() * static_cast<long long>(object.mesh.positions.size()));
}

void BM_VerticesFromTransformKeys(benchmark::State& state) { run(state, fixture().keyed); }
void BM_VerticesFromExactChain(benchmark::State& state) { run(state, fixture().chain); }
void BM_VerticesFromExactSkin(benchmark::State& state) { run(state, fixture().skin); }

}  // namespace

BENCHMARK(BM_VerticesFromTransformKeys)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_VerticesFromExactChain)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_VerticesFromExactSkin)->Unit(benchmark::kMicrosecond);

}  // namespace clipblur
