#include "renderer/stochastic/stochastic_renderer.h"

#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "renderer/camera_path.h"
#include "renderer/frame_motion.h"
#include "renderer/sampling/pixel_samples.h"
#include "renderer/shading/shading.h"
#include "renderer/stopwatch.h"
#include "renderer/tiles.h"
#include "renderer/visibility/embree_scene.h"
#include "renderer/worker_threads.h"
#include "scene/camera.h"
#include "scene/error.h"
#include "scene/shutter_curve.h"

namespace clipblur {

namespace {

// 4096 steps: the table's deviation from the camera's arc is below 1e-9 rad for turns up to 0.36 rad.
constexpr int kCameraTableSteps = 4096;

struct TileCounters {
    long long primary_rays = 0;
    long long shadow_rays = 0;
    long long depth_rays = 0;  // depth AOV: the samples traced again at mid-shutter
};

}  // namespace

RenderResult renderStochastic(const RenderJob& job, int frame, const RenderCallbacks& callbacks) {
    const auto start = Clock::now();
    const Scene& scene = job.scene;
    const int width = scene.film.width;
    const int height = scene.film.height;
    const int samples = job.render.samples;
    if (samples < 1) throw Error(ExitCode::Render, "stochastic rendering needs at least 1 sample per pixel");
    if (scene.camera.keys.empty()) throw Error(ExitCode::Render, "the scene has no camera key");
    const double t0 = frame + job.shutter.open;
    const double t1 = frame + job.shutter.close;
    const ShutterCurve curve(job.shutter, frame);

    const FrameMotion motion(scene, t0, t1);
    EmbreeDevice device;
    const EmbreeScene visibility(device, motion);
    const Shader shader(motion, job.render.shadows ? &visibility : nullptr);
    const double build_seconds = secondsSince(start);

    const Projection projection(width, height, scene.camera.vfov_degrees);
    // Per ray the camera comes from a table, not from trigonometry (its bound: camera_path.h).
    const CameraTable camera_table(motion.cameraPath(), t0, t1, kCameraTableSteps);
    const CameraFrame camera_open = motion.camera(t0);
    const CameraFrame camera_close = motion.camera(t1);
    // The depth AOV is what is seen at mid-shutter: each sample's spatial position traced again at that time.
    const double t_mid = 0.5 * (t0 + t1);
    const CameraFrame camera_mid = motion.camera(t_mid);
    // Tiles cover the render window only; every pixel's samples are keyed by its film position, so a
    // window renders exactly the pixels the whole film would.
    const PixelBounds window = renderWindow(job);
    const TileGrid grid(window.width(), window.height(), job.render.tile_size);
    const OutputSettings& out = job.output;

    RenderResult result;
    result.image = Image::make(width, height, window, outputChannels(out));
    Image& image = result.image;
    float* rgba[4];
    for (int c = 0; c < 4; ++c) rgba[c] = image.channels[static_cast<std::size_t>(c)].values.data();
    float* z_out = out.aov_depth ? image.find("Z")->values.data() : nullptr;
    float* cov_out = out.aov_coverage ? image.find("coverage")->values.data() : nullptr;
    float* mx_out = out.aov_motion ? image.find("motion.x")->values.data() : nullptr;
    float* my_out = out.aov_motion ? image.find("motion.y")->values.data() : nullptr;
    const bool count_objects = out.cryptomatte.enabled;
    if (count_objects) result.objects.pixels.resize(image.channels[0].values.size());

    const std::uint64_t frame_key = static_cast<std::uint64_t>(static_cast<std::int64_t>(frame));
    const long long total_tiles = grid.count();
    std::mutex progress_mutex;
    long long tiles_done = 0;
    TileCounters totals;
    bool cancelled = false;
    const auto render_start = Clock::now();

    tbb::parallel_for(tbb::blocked_range<int>(0, grid.count(), 1), [&](const tbb::blocked_range<int>& range) {
        std::vector<SpaceTimeSample> pixel_samples;
        std::vector<std::uint32_t> scratch;
        TileCounters counters;
        for (int task = range.begin(); task != range.end(); ++task) {
            if (callbacks.cancel && callbacks.cancel->load(std::memory_order_relaxed)) {
                std::lock_guard lock(progress_mutex);
                cancelled = true;
                continue;
            }
            const PixelBounds tile = grid.tile(task);
            for (int y = window.y0 + tile.y0; y < window.y0 + tile.y1; ++y) {
                for (int x = window.x0 + tile.x0; x < window.x0 + tile.x1; ++x) {
                    const std::size_t film_pixel = static_cast<std::size_t>(y) * width + x;
                    const std::size_t pixel = image.index(x, y);
                    generatePixelSamples(HashRng::forKey(job.render.seed, frame_key, film_pixel), samples,
                                         pixel_samples, scratch);
                    glm::dvec3 colour(0.0);
                    double covered = 0.0;
                    double depth_sum = 0.0, depth_covered = 0.0;
                    glm::dvec2 motion_sum(0.0);
                    double motion_count = 0.0;
                    std::vector<ObjectShare> shares;  // samples per object, for ID mattes
                    for (const SpaceTimeSample& s : pixel_samples) {
                        // Stratified in u, so stratified in the curve's mass (a box: its time).
                        const double t = curve.box() ? t0 + (t1 - t0) * s.time : curve.timeAt(s.time);
                        const CameraFrame camera = camera_table.at(t);
                        const glm::dvec2 p = projection.toImagePlane(glm::dvec2(x + s.x, y + s.y));
                        // Unnormalised, with e3.dir = 1: the hit distance is the camera depth.
                        const glm::dvec3 dir = camera.e3 + p.x * camera.e1 + p.y * camera.e2;
                        const EmbreeHit hit = visibility.intersect(camera.position, dir, t);
                        ++counters.primary_rays;
                        if (z_out) {
                            const glm::dvec3 mid_dir = camera_mid.e3 + p.x * camera_mid.e1 + p.y * camera_mid.e2;
                            const EmbreeHit mid = visibility.intersect(camera_mid.position, mid_dir, t_mid);
                            ++counters.depth_rays;
                            if (mid.hit) {
                                depth_sum += mid.distance;
                                depth_covered += 1.0;
                            }
                        }
                        // Premultiplied colour: a miss adds nothing (the background is the compositor's).
                        if (!hit.hit) continue;
                        const SurfacePoint point{hit.object, hit.triangle, hit.u, hit.v, t};
                        // The surface as Embree hit it: no motion evaluated again per sample.
                        const double normal_length = glm::length(hit.normal);
                        SurfaceGeometry surface;
                        surface.position = camera.position + hit.distance * dir;
                        surface.normal = normal_length > 0.0 ? hit.normal / normal_length : glm::dvec3(0.0);
                        surface.object_position = shader.objectPosition(point);
                        // Point samples: textures are read unfiltered, so the converged average is the
                        // area integral of the image the clipped method filters.
                        shader.addCornerAttributes(point, surface);
                        colour += shader.shade(point, surface, camera.position, &counters.shadow_rays);
                        covered += 1.0;
                        if (count_objects) addShare(shares, hit.object, 1.0);
                        if (mx_out) {
                            SurfacePoint at = point;
                            at.time = t0;
                            const ImagePoint a = projectToImagePlane(camera_open, shader.geometry(at).position);
                            at.time = t1;
                            const ImagePoint b = projectToImagePlane(camera_close, shader.geometry(at).position);
                            if (a.depth > 0.0 && b.depth > 0.0) {
                                motion_sum += projection.toRaster(b.p) - projection.toRaster(a.p);
                                motion_count += 1.0;
                            }
                        }
                    }
                    const double inv = 1.0 / samples;
                    rgba[0][pixel] = static_cast<float>(colour.r * inv);
                    rgba[1][pixel] = static_cast<float>(colour.g * inv);
                    rgba[2][pixel] = static_cast<float>(colour.b * inv);
                    rgba[3][pixel] = static_cast<float>(covered * inv);
                    if (cov_out) cov_out[pixel] = static_cast<float>(covered * inv);
                    if (count_objects) {
                        for (ObjectShare& s : shares) s.coverage *= inv;
                        result.objects.pixels[pixel] = std::move(shares);
                    }
                    if (z_out)
                        z_out[pixel] = depth_covered > 0.0 ? static_cast<float>(depth_sum / depth_covered)
                                                     : std::numeric_limits<float>::infinity();
                    if (mx_out) {
                        const glm::dvec2 m = motion_count > 0.0 ? motion_sum / motion_count : glm::dvec2(0.0);
                        mx_out[pixel] = static_cast<float>(m.x);
                        my_out[pixel] = static_cast<float>(m.y);
                    }
                }
            }
            std::lock_guard lock(progress_mutex);
            ++tiles_done;
            if (callbacks.progress) callbacks.progress(tiles_done, total_tiles);
        }
        std::lock_guard lock(progress_mutex);
        totals.primary_rays += counters.primary_rays;
        totals.shadow_rays += counters.shadow_rays;
        totals.depth_rays += counters.depth_rays;
    });
    if (cancelled) throw Error(ExitCode::Interrupted, "render cancelled");

    StochasticStats stats;
    stats.scene_build_seconds = build_seconds;
    stats.render_seconds = secondsSince(render_start);
    const EmbreeSceneStats& vs = visibility.stats();
    stats.samples_per_pixel = samples;
    stats.samples = static_cast<long long>(window.area()) * samples;
    stats.primary_rays = totals.primary_rays;
    stats.shadow_rays = totals.shadow_rays;
    stats.depth_rays = totals.depth_rays;
    stats.tiles = total_tiles;
    stats.triangles = vs.triangles;
    stats.dropped_triangles = vs.dropped_triangles;
    stats.moving_objects = vs.moving_objects;
    stats.capped_time_step_objects = vs.capped_objects;
    stats.max_time_steps = vs.max_time_steps;
    stats.vertex_evaluations = vs.vertex_evaluations;
    result.stats.method = stats;
    return result;
}

}  // namespace clipblur
