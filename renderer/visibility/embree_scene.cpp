#include "renderer/visibility/embree_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <malloc.h>
#include <string>
#include <utility>

#include <tbb/task_arena.h>

#include "scene/camera.h"
#include "scene/error.h"
#include "scene/object_motion.h"

namespace clipblur {

namespace {

// Embree's commit skips primitives whose vertices leave this range (or are NaN/Inf).
constexpr float kEmbreeCoordinateLimit = 1.844e18f;

// Owns a geometry until it is attached and committed.
class GeometryHandle {
public:
    GeometryHandle(RTCDevice device, RTCGeometryType type) : geometry_(rtcNewGeometry(device, type)) {}
    ~GeometryHandle() {
        if (geometry_) rtcReleaseGeometry(geometry_);
    }
    GeometryHandle(const GeometryHandle&) = delete;
    GeometryHandle& operator=(const GeometryHandle&) = delete;
    RTCGeometry get() const { return geometry_; }

private:
    RTCGeometry geometry_;
};

// Largest image-plane deviation, in pixels, between the true positions at a segment's midpoint time and
// the chord midpoints. With d = x - camera and depth z = e3.d, the image point is p = (e1.d, e2.d)/z and a
// displacement D moves it by |dp| <= |D| (1 + |p|) / z. Vertices behind the camera have no image point
// and are skipped.
double chordErrorPixels(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b,
                        const std::vector<glm::dvec3>& mid, const CameraFrame& camera, double pixels_per_unit) {
    double worst = 0.0;
    for (std::size_t i = 0; i < mid.size(); ++i) {
        const glm::dvec3 d = mid[i] - camera.position;
        const double depth = glm::dot(camera.e3, d);
        if (!(depth > 0.0)) continue;
        const glm::dvec2 p(glm::dot(camera.e1, d) / depth, glm::dot(camera.e2, d) / depth);
        const double deviation = glm::length(mid[i] - 0.5 * (a[i] + b[i]));
        const double px = deviation * (1.0 + glm::length(p)) / depth * pixels_per_unit;
        if (!(px <= worst)) worst = px;  // NaN propagates as "too large"
    }
    return worst;
}

bool validCoordinate(float c) { return std::isfinite(c) && std::fabs(c) < kEmbreeCoordinateLimit; }

void checkMesh(const Object& object) {
    const std::size_t n = object.mesh.positions.size();
    for (const auto& tri : object.mesh.triangles)
        for (std::uint32_t index : tri)
            if (index >= n)
                throwSceneError(object.loc, "object '" + object.name + "' has vertex index " + std::to_string(index) +
                                                " but only " + std::to_string(n) + " vertices");
    for (const auto& key : object.deformation)
        if (key.positions.size() != n)
            throwSceneError(object.loc, "object '" + object.name + "' has a deformation key with " +
                                            std::to_string(key.positions.size()) + " vertices instead of " +
                                            std::to_string(n));
}

}  // namespace

EmbreeScene::EmbreeScene(const EmbreeDevice& device, const FrameMotion& motion, const std::vector<char>* leave_out,
                         Layout layout)
    : device_(&device), t0_(motion.t0()), t1_(motion.t1()) {
    const Scene& scene = motion.scene();
    const double t0 = t0_, t1 = t1_;
    if (!(t1 >= t0)) throw Error(ExitCode::Render, "shutter window must satisfy t0 <= t1");

    const Projection projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
    const double ppu = projection.pixelsPerUnit();
    steps_.assign(scene.objects.size(), 0);

    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        if (object.mesh.triangles.empty() || (leave_out && (*leave_out)[o])) continue;
        checkMesh(object);
        const std::size_t nv = object.mesh.positions.size();

        // Double-precision positions per time step and at the segments' midpoints, scoped to the object:
        // 24 bytes a vertex a step (hundreds of MB for a million triangles at 17 steps), gone before the
        // BVH build below, which needs the most memory of the frame.
        std::vector<std::vector<glm::dvec3>> steps(1), mids;
        motion.vertices(o, t0, steps[0]);
        stats_.vertex_evaluations += static_cast<long long>(nv);
        if (t1 > t0 && !motion.shutter().objectStill(o)) {
            ++stats_.moving_objects;
            steps.resize(2);
            motion.vertices(o, t1, steps[1]);
            stats_.vertex_evaluations += static_cast<long long>(nv);
            while (true) {
                const std::size_t segments = steps.size() - 1;
                mids.resize(segments);
                double worst = 0.0;
                for (std::size_t s = 0; s < segments; ++s) {
                    const double tm = t0 + (t1 - t0) * (static_cast<double>(s) + 0.5) / static_cast<double>(segments);
                    motion.vertices(o, tm, mids[s]);
                    stats_.vertex_evaluations += static_cast<long long>(nv);
                    worst = std::max(worst, chordErrorPixels(steps[s], steps[s + 1], mids[s],
                                                             motion.camera(tm), ppu));
                }
                if (worst <= kMaxChordErrorPixels) break;
                if (2 * segments + 1 > RTC_MAX_TIME_STEP_COUNT) {
                    ++stats_.capped_objects;
                    break;
                }
                // Interleave: the midpoints become steps, halving every segment.
                std::vector<std::vector<glm::dvec3>> refined;
                refined.reserve(2 * segments + 1);
                for (std::size_t s = 0; s < segments; ++s) {
                    refined.push_back(std::move(steps[s]));
                    refined.push_back(std::move(mids[s]));
                }
                refined.push_back(std::move(steps.back()));
                steps = std::move(refined);
                mids.clear();
            }
        }

        const auto step_count = static_cast<unsigned>(steps.size());
        Geometry geometry{.object = static_cast<int>(o), .steps = std::vector<std::vector<float>>(step_count), .indices = {}};
        std::vector<bool> bad_vertex(nv, false);
        for (unsigned s = 0; s < step_count; ++s) {
            std::vector<float>& v = geometry.steps[s];
            v.assign(3 * nv + 1, 0.0f);  // one float past the last vertex: Embree reads 16 bytes a vertex
            for (std::size_t i = 0; i < nv; ++i) {
                for (int c = 0; c < 3; ++c) {
                    v[3 * i + c] = static_cast<float>(steps[s][i][c]);
                    if (!validCoordinate(v[3 * i + c])) bad_vertex[i] = true;
                }
            }
            std::vector<glm::dvec3>().swap(steps[s]);
        }
        geometry.indices.resize(3 * object.mesh.triangles.size());
        for (std::size_t t = 0; t < object.mesh.triangles.size(); ++t) {
            const auto& tri = object.mesh.triangles[t];
            for (int c = 0; c < 3; ++c) geometry.indices[3 * t + c] = tri[c];
            if (bad_vertex[tri[0]] || bad_vertex[tri[1]] || bad_vertex[tri[2]]) ++stats_.dropped_triangles;
        }
        object_of_geometry_.push_back(static_cast<int>(o));  // geometry IDs follow the order of attachment
        geometries_.push_back(std::move(geometry));
        steps_[o] = static_cast<int>(step_count);
        stats_.triangles += static_cast<long long>(object.mesh.triangles.size());
        stats_.max_time_steps = std::max(stats_.max_time_steps, static_cast<int>(step_count));
    }
#ifdef __GLIBC__
    // The steps were freed to the heap, whose pages glibc keeps; the build allocates its own (mmap).
    malloc_trim(0);
#endif
    int moving_steps = 0;  // the moving objects' common step count; -1 when they differ
    for (const Geometry& g : geometries_) {
        const auto n = static_cast<int>(g.steps.size());
        if (n > 1) moving_steps = moving_steps == 0 || moving_steps == n ? n : -1;
    }
    const int segments = moving_steps - 1;
    // A triangle invalid at one step is dropped from the whole scene but would be kept in the segments
    // that do not hold that step.
    if (layout == Layout::PerSegment && segments > 1 && (segments & (segments - 1)) == 0 && stats_.dropped_triangles == 0) {
        segment_count_ = segments;
        segments_ = std::make_unique<Segment[]>(static_cast<std::size_t>(segments));
    } else {
        scene_ = buildScene(0, 0);
    }
}

EmbreeScene::SceneHandle EmbreeScene::buildScene(std::size_t first, std::size_t count) const {
    SceneHandle scene(rtcNewScene(device_->get()));
    device_->check("creating a scene");
    for (std::size_t id = 0; id < geometries_.size(); ++id) {
        const Geometry& g = geometries_[id];
        const std::size_t begin = g.steps.size() > 1 ? first : 0;
        const std::size_t steps = g.steps.size() > 1 ? (count == 0 ? g.steps.size() : count) : 1;
        const std::size_t nv = g.steps[0].size() / 3;
        GeometryHandle geometry(device_->get(), RTC_GEOMETRY_TYPE_TRIANGLE);
        if (steps > 1) rtcSetGeometryTimeStepCount(geometry.get(), static_cast<unsigned>(steps));
        for (std::size_t s = 0; s < steps; ++s)
            rtcSetSharedGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_VERTEX, static_cast<unsigned>(s), RTC_FORMAT_FLOAT3,
                                       g.steps[begin + s].data(), 0, 3 * sizeof(float), nv);
        rtcSetSharedGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, g.indices.data(), 0,
                                   3 * sizeof(std::uint32_t), g.indices.size() / 3);
        device_->check("sharing the buffers of object " + std::to_string(g.object));
        rtcCommitGeometry(geometry.get());
        const unsigned attached = rtcAttachGeometry(scene.get(), geometry.get());
        device_->check("adding object " + std::to_string(g.object));
        if (attached != id) throw Error(ExitCode::Render, "Embree numbered a geometry out of attachment order");
    }
    rtcCommitScene(scene.get());
    device_->check("building the acceleration structure");
    return scene;
}

std::pair<std::size_t, float> EmbreeScene::segmentAt(double t) const {
    // Embree's own time segment and fraction, exact in float: segment_count_ is a power of two.
    const auto segments = static_cast<float>(segment_count_);
    const float scaled = static_cast<float>(embreeTime(t)) * segments;
    const float index = std::clamp(std::floor(scaled), 0.0f, segments - 1.0f);
    return {static_cast<std::size_t>(index), scaled - index};
}

std::pair<RTCScene, float> EmbreeScene::sceneAt(double t) const {
    if (segment_count_ == 0) return {scene_.get(), static_cast<float>(embreeTime(t))};
    const auto [s, fraction] = segmentAt(t);
    Segment& segment = segments_[s];
    RTCScene scene = segment.ready.load(std::memory_order_acquire);
    if (!scene) {
        std::lock_guard lock(segment.mutex);
        // Isolated: while Embree's build waits for its own tasks this thread takes no other ray's task,
        // which could ask for this segment again and wait for itself.
        if (!segment.scene) tbb::this_task_arena::isolate([&, s = s] { segment.scene = buildScene(s, 2); });
        scene = segment.scene.get();
        segment.ready.store(scene, std::memory_order_release);
    }
    return {scene, fraction};
}

void EmbreeScene::releaseSegmentScenes(std::span<const double> keep) const {
    if (segment_count_ == 0) return;
    std::vector<char> kept(static_cast<std::size_t>(segment_count_), 0);
    for (const double t : keep) kept[segmentAt(t).first] = 1;
    bool freed = false;
    for (std::size_t s = 0; s < kept.size(); ++s) {
        Segment& segment = segments_[s];
        if (kept[s] || !segment.scene) continue;
        std::lock_guard lock(segment.mutex);
        segment.ready.store(nullptr, std::memory_order_release);
        segment.scene.reset();
        freed = true;
    }
#ifdef __GLIBC__
    // The build ran on worker threads, whose heap arenas keep freed pages from the main thread's
    // allocations: 1920x1080 dense_mesh peaked 153 MiB higher without this.
    if (freed) malloc_trim(0);
#endif
}

int EmbreeScene::segmentScenesBuilt() const {
    int built = 0;
    for (int s = 0; s < segment_count_; ++s) built += segments_[static_cast<std::size_t>(s)].scene ? 1 : 0;
    return built;
}

double EmbreeScene::embreeTime(double t) const {
    if (!(t1_ > t0_)) return 0.0;
    return std::clamp((t - t0_) / (t1_ - t0_), 0.0, 1.0);
}

EmbreeHit EmbreeScene::intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = static_cast<float>(origin.x);
    rh.ray.org_y = static_cast<float>(origin.y);
    rh.ray.org_z = static_cast<float>(origin.z);
    rh.ray.dir_x = static_cast<float>(direction.x);
    rh.ray.dir_y = static_cast<float>(direction.y);
    rh.ray.dir_z = static_cast<float>(direction.z);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    const auto [scene, time] = sceneAt(t);
    rh.ray.time = time;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    EmbreeHit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.object = object_of_geometry_[rh.hit.geomID];
    hit.triangle = rh.hit.primID;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    hit.distance = rh.ray.tfar;
    hit.normal = glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    return hit;
}

bool EmbreeScene::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double max_distance,
                           double t) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    ray.org_x = static_cast<float>(origin.x);
    ray.org_y = static_cast<float>(origin.y);
    ray.org_z = static_cast<float>(origin.z);
    ray.dir_x = static_cast<float>(direction.x);
    ray.dir_y = static_cast<float>(direction.y);
    ray.dir_z = static_cast<float>(direction.z);
    ray.tnear = 0.0f;
    ray.tfar = static_cast<float>(max_distance);
    const auto [scene, time] = sceneAt(t);
    ray.time = time;
    ray.mask = 0xffffffffu;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(scene, &context, &ray);
    return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace clipblur
