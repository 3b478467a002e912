// The floor a stochastic renderer is held to: a minimal motion-blur ray caster over the same Embree
// scene clipblur's stochastic method builds (same time-stepped geometry, same camera keys, same pixel
// and projection conventions), with nothing else in the loop. Per sample: stratified pixel jitter,
// Latin-hypercube time, the camera basis turned (Rodrigues) between its keys, one rtcIntersect1, and the
// material's albedo times ambient plus directional or point lights with Embree's geometric normal
// (unshadowed). Written as a user who knows Embree would write it, not from the renderer's code.
//
//   clipblur_plain_loop JOB.yaml --spp N --out IMAGE.exr [--threads N] [--seed S] [--set key=value]...
// Prints "seconds S samples N" (loop time, scene build excluded) on stdout.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <embree3/rtcore.h>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "io/image_writer.h"
#include "io/job_loader.h"
#include "renderer/image.h"
#include "renderer/shading/shading.h"
#include "renderer/visibility/embree_device.h"
#include "renderer/visibility/embree_scene.h"
#include "scene/camera.h"
#include "scene/error.h"

namespace {

using namespace clipblur;

// splitmix64: a pixel's stream from (seed, pixel), then successive draws.
struct Rng {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
};

struct Key {
    double time;
    glm::dvec3 position;
    glm::dmat3 basis;  // columns e1 (up), e2 (right), e3 (view)
    glm::dvec3 axis;   // the turn to the next key: unit axis and angle
    double angle = 0.0;
};

std::vector<Key> cameraKeys(const Camera& camera) {
    std::vector<Key> keys;
    for (const CameraKey& k : camera.keys) {
        const CameraFrame f = makeCameraFrame(k.position, k.view, k.up);
        keys.push_back({k.time, k.position, f.basis(), glm::dvec3(0, 0, 1), 0.0});
    }
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
        const glm::dquat q = glm::quat_cast(keys[i + 1].basis * glm::transpose(keys[i].basis));
        const double angle = glm::angle(q);
        if (angle > 0.0) {
            keys[i].axis = glm::axis(q);
            keys[i].angle = angle;
        }
    }
    return keys;
}

// Rodrigues: v turned by `angle` about the unit `axis`, with its sine and cosine given.
glm::dvec3 turn(const glm::dvec3& v, const glm::dvec3& axis, double c, double s) {
    return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}

// The camera at absolute time t: position lerped, basis turned at a constant rate between the keys.
glm::dmat3 cameraAt(const std::vector<Key>& keys, double t, glm::dvec3& position) {
    std::size_t i = 0;
    while (i + 2 < keys.size() && keys[i + 1].time <= t) ++i;
    if (keys.size() == 1 || t <= keys.front().time) {
        position = keys.front().position;
        return keys.front().basis;
    }
    const Key& a = keys[i];
    const Key& b = keys[i + 1];
    const double f = std::clamp((t - a.time) / (b.time - a.time), 0.0, 1.0);
    position = glm::mix(a.position, b.position, f);
    const double c = std::cos(f * a.angle), s = std::sin(f * a.angle);
    return glm::dmat3(turn(a.basis[0], a.axis, c, s), turn(a.basis[1], a.axis, c, s), turn(a.basis[2], a.axis, c, s));
}

glm::dvec3 shadeHit(const Scene& scene, const EmbreeScene& embree, const RTCRayHit& rh) {
    const Object& object = scene.objects[static_cast<std::size_t>(embree.objectOfGeometry(rh.hit.geomID))];
    const Material& material = scene.materials[static_cast<std::size_t>(object.material)];
    const auto& tri = object.mesh.triangles[rh.hit.primID];
    const auto& rest = object.mesh.positions;
    const double u = rh.hit.u, v = rh.hit.v;
    const glm::dvec3 object_position = (1.0 - u - v) * rest[tri[0]] + u * rest[tri[1]] + v * rest[tri[2]];
    glm::dvec3 light = scene.ambient;
    const bool lit = material.model == ShadingModel::Lit;
    // The back-face test only where something but ambient light is shaded (the loop's original shortcut).
    if (!scene.lights.empty() || !lit || material.emission != glm::dvec3(0.0)) {
        glm::dvec3 n = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
        const glm::dvec3 dir(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
        if (glm::dot(n, dir) > 0.0) {
            if (!material.two_sided) return glm::dvec3(0.0);
            n = -n;
        }
        if (!lit) return albedo(material, object_position);
        const glm::dvec3 hit = glm::dvec3(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z) + double(rh.ray.tfar) * dir;
        for (const Light& l : scene.lights) light += lightIrradiance(l, hit, n);
    }
    return albedo(material, object_position) * light + material.emission;
}

// The shutter time whose share of the shutter curve's integral is u: bisection on the trapezoid sums,
// so the peer shares no code with the renderer's closed-form inverse.
double curveTime(const Shutter& shutter, double t0, double u) {
    const auto integral = [&](double t) {  // from open to t, in frames relative to the frame
        double sum = 0.0;
        for (std::size_t i = 0; i + 1 < shutter.curve.size(); ++i) {
            const ShutterPoint a = shutter.curve[i], b = shutter.curve[i + 1];
            const double end = std::min(t, b.time);
            if (end <= a.time) break;
            const double w_end = a.weight + (b.weight - a.weight) * (end - a.time) / (b.time - a.time);
            sum += 0.5 * (a.weight + w_end) * (end - a.time);
        }
        return sum;
    };
    const double target = u * integral(shutter.close);
    double lo = shutter.open, hi = shutter.close;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (integral(mid) < target ? lo : hi) = mid;
    }
    return t0 + (0.5 * (lo + hi) - shutter.open);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Minimal Embree motion-blur loop: the stochastic peer's floor"};
    std::string job_path, out_path;
    std::vector<std::string> overrides;
    int spp = 64, threads = 0;
    std::uint64_t seed = 1;
    app.add_option("job", job_path, "Render job (YAML or JSON)")->required();
    app.add_option("--spp", spp, "Samples per pixel")->check(CLI::Range(1, 1 << 20));
    app.add_option("--out", out_path, "Output EXR")->required();
    app.add_option("--threads", threads, "Threads (0: all)");
    app.add_option("--seed", seed, "Random seed");
    app.add_option("--set", overrides, "Job override key.path=value");
    CLI11_PARSE(app, argc, argv);
    try {
        const std::size_t concurrency = threads > 0 ? std::size_t(threads) : tbb::this_task_arena::max_concurrency();
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, concurrency);
        const RenderJob job = loadJob(job_path, overrides);
        const Scene& scene = job.scene;
        const int width = scene.film.width, height = scene.film.height;
        const double t0 = job.frames.first + job.shutter.open, t1 = job.frames.first + job.shutter.close;
        EmbreeDevice device;
        const EmbreeScene embree(device, FrameMotion(scene, t0, t1));
        const std::vector<Key> keys = cameraKeys(scene.camera);
        const Projection projection(width, height, scene.camera.vfov_degrees);
        Image image = Image::make(width, height, {"R", "G", "B", "A"});

        const int side = std::max(1, static_cast<int>(std::sqrt(double(spp))));  // side^2 strata, the rest random
        const auto start = std::chrono::steady_clock::now();
        tbb::parallel_for(0, height, [&](int y) {
            std::vector<std::uint32_t> time_strata(static_cast<std::size_t>(spp));
            for (int x = 0; x < width; ++x) {
                Rng rng{seed * 0x9e3779b97f4a7c15ULL + std::uint64_t(y) * width + x};
                std::iota(time_strata.begin(), time_strata.end(), 0u);
                for (int i = spp - 1; i > 0; --i) std::swap(time_strata[i], time_strata[rng.next() % (i + 1)]);
                glm::dvec3 sum(0.0);
                double alpha = 0.0;
                for (int s = 0; s < spp; ++s) {
                    double jx = rng.uniform(), jy = rng.uniform();
                    if (s < side * side) {
                        jx = (s % side + jx) / side;
                        jy = (s / side + jy) / side;
                    }
                    const double stratum = time_strata[s] + rng.uniform();
                    const double t = job.shutter.curve.empty() ? t0 + (t1 - t0) * stratum / spp
                                                               : curveTime(job.shutter, t0, stratum / spp);
                    glm::dvec3 eye;
                    const glm::dmat3 basis = cameraAt(keys, t, eye);
                    const glm::dvec2 p = projection.toImagePlane(glm::dvec2(x + jx, y + jy));
                    const glm::dvec3 dir = basis[2] + p.x * basis[0] + p.y * basis[1];
                    RTCIntersectContext context;
                    rtcInitIntersectContext(&context);
                    RTCRayHit rh{};
                    rh.ray = {float(eye.x), float(eye.y), float(eye.z), 0.0f, float(dir.x), float(dir.y), float(dir.z),
                              float(embree.embreeTime(t)), std::numeric_limits<float>::infinity(), 0xffffffffu, 0, 0};
                    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    rtcIntersect1(embree.get(), &context, &rh);
                    // Premultiplied like clipblur's own output: a miss adds no colour.
                    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
                    sum += shadeHit(scene, embree, rh);
                    alpha += 1.0;
                }
                const std::size_t i = image.index(x, y);
                for (int c = 0; c < 3; ++c) image.channels[std::size_t(c)].values[i] = float(sum[c] / spp);
                image.channels[3].values[i] = float(alpha / spp);
            }
        });
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ImageMetadata metadata;
        metadata.method = "plain_embree_loop";
        metadata.samples = spp;
        metadata.seed = seed;
        metadata.render_seconds = seconds;
        writeExr(out_path, image, metadata, ExrFormat{false, ExrCompression::Zip});
        std::cout << "seconds " << seconds << " samples " << spp << "\n";
    } catch (const Error& e) {
        std::cerr << "clipblur_plain_loop: " << e.what() << "\n";
        return static_cast<int>(e.code());
    }
    return 0;
}
