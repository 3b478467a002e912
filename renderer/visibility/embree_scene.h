#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "renderer/visibility/embree_device.h"
#include "renderer/frame_motion.h"
#include "scene/scene.h"

namespace clipblur {

struct EmbreeHit {
    bool hit = false;
    int object = -1;             // index into Scene::objects
    std::uint32_t triangle = 0;  // index into the object's Mesh::triangles
    double u = 0.0;              // Embree barycentrics: p = (1-u-v) v0 + u v1 + v v2
    double v = 0.0;
    double distance = 0.0;       // ray parameter: with an unnormalised direction, in units of that direction
    glm::dvec3 normal{0.0};      // unnormalised, along (v1-v0) x (v2-v0) of the triangle as hit at the ray's time
};

struct EmbreeSceneStats {
    long long triangles = 0;          // uploaded to Embree
    long long dropped_triangles = 0;  // with a NaN/Inf/huge coordinate at some time step: Embree skips them
    long long moving_objects = 0;
    long long capped_objects = 0;     // needed more than the maximum time steps for the 0.1 px chord bound
    int max_time_steps = 1;
    long long vertex_evaluations = 0;
};

// The scene over one frame's shutter window [t0, t1] (absolute frames) as an Embree scene; ray time t maps
// to Embree's [0, 1] linearly. t0 == t1 gives a still scene at that instant.
//
// Moving objects are uploaded as time-stepped vertex buffers rather than as rigid instances with
// rtcSetGeometryTransformQuaternion: steps handle deformation blur, non-uniform scale and several
// transform keys inside the shutter in one mechanism, and the instance route would still need steps for
// deforming meshes. Because Embree interpolates linearly between steps, a rotating vertex follows a chord
// instead of its arc; the step count is doubled (2, 3, 5, ..., 129 steps) until the measured
// midpoint deviation of every vertex, projected to the image at the midpoint time, is below 0.1 px.
// The deviation of an arc from its chord is largest at the middle, so this is the chord error.
//
// Layout::PerSegment trades that one BVH over every step for one per pair of adjacent steps, built when
// a ray first asks for a time in it: a BVH over 16 time segments of a million triangles takes about
// 1 GB to keep and 1.7 GB to build (temporal splits), one over a segment about a tenth of that, and a
// frame's fragment sets ask for two or three times. A ray at time tau meets the same vertices either way:
// Embree's time segment and fraction (its getTimeSegment: tau x segments, floor, clamp) are exact in
// float for a power-of-two segment count, and a one-segment scene given that fraction uses it unchanged.
// Only the order in which the two BVHs visit triangles differs, which decides nothing but exact ties.
// It applies when every moving object has the same step count (else one scene holds all the steps), and
// suits few distinct ray times: rays at every time (shadows, stochastic) would build every segment's.
//
// The EmbreeDevice must outlive the scene: its error callback records into the device object.
class EmbreeScene {
public:
    static constexpr double kMaxChordErrorPixels = 0.1;
    enum class Layout { Whole, PerSegment };

    // `leave_out` (per object, optional): objects not to add, such as a still backdrop rendered on its own.
    EmbreeScene(const EmbreeDevice& device, const FrameMotion& motion, const std::vector<char>* leave_out = nullptr,
                Layout layout = Layout::Whole);
    EmbreeScene(EmbreeScene&& other) noexcept = default;
    EmbreeScene& operator=(EmbreeScene&& other) noexcept = default;
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Closest hit along origin + s * direction, s in (0, inf), at absolute time t.
    EmbreeHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t) const;
    // Any hit for s in (0, max_distance) at absolute time t.
    bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double max_distance, double t) const;

    double embreeTime(double t) const;
    // Scene::objects index of an Embree geometry ID (objects without triangles have none).
    int objectOfGeometry(unsigned geometry) const { return object_of_geometry_[geometry]; }
    double t0() const { return t0_; }
    double t1() const { return t1_; }
    int timeSteps(int object) const { return steps_[static_cast<std::size_t>(object)]; }
    const EmbreeSceneStats& stats() const { return stats_; }
    // Segment scenes built so far (Layout::PerSegment; 0 otherwise).
    int segmentScenesBuilt() const;
    // Frees the segment scenes no time in `keep` (absolute) falls in; a ray that asks for one again
    // rebuilds it, so results do not change: a render frees those its next fragment sets will not use
    // (dense_mesh at 1920x1080 peaked about 300 MiB higher with them kept). Not while rays are in flight.
    void releaseSegmentScenes(std::span<const double> keep) const;
    // The scene holding every time step (Layout::Whole).
    RTCScene get() const { return scene_.get(); }

private:
    struct SceneRelease {
        void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
    };
    using SceneHandle = std::unique_ptr<RTCSceneTy, SceneRelease>;
    // One object's vertex positions per time step (float xyz, padded for Embree's 16-byte loads) and its
    // triangles, shared with every scene built from them.
    struct Geometry {
        int object = -1;
        std::vector<std::vector<float>> steps;
        std::vector<std::uint32_t> indices;
    };
    struct Segment {
        std::mutex mutex;                 // held while the scene is built or freed
        SceneHandle scene;
        std::atomic<RTCScene> ready{nullptr};  // scene.get() once built: read by rays without the lock
    };
    // A scene of steps [first, first + count) of the moving objects (the still ones have one); count 0:
    // every object's own steps.
    SceneHandle buildScene(std::size_t first, std::size_t count) const;
    // The scene and Embree ray time for absolute time t.
    std::pair<RTCScene, float> sceneAt(double t) const;
    // Layout::PerSegment: the segment absolute time t falls in, and t's fraction within it.
    std::pair<std::size_t, float> segmentAt(double t) const;

    const EmbreeDevice* device_ = nullptr;
    std::vector<Geometry> geometries_;
    SceneHandle scene_;  // Layout::Whole
    int segment_count_ = 0;  // Layout::PerSegment: the moving objects' common step count - 1; else 0
    std::unique_ptr<Segment[]> segments_;
    double t0_ = 0.0;
    double t1_ = 0.0;
    std::vector<int> object_of_geometry_;  // geomID -> object index
    std::vector<int> steps_;               // per object; 0 for objects without triangles
    EmbreeSceneStats stats_;
};

}  // namespace clipblur
