#include "io/exr_frame_header.h"

#include <cmath>
#include <numeric>
#include <charconv>
#include <string>

#include <glm/mat4x4.hpp>

namespace clipblur {

namespace {

// glm matrices are column-major for column vectors (p' = M p); Imath's row-vector matrix is the
// transpose, and glm's column-major storage of M is exactly Imath's row-major storage of M^T.
ExrMatrix toExr(const glm::dmat4& m) {
    ExrMatrix out{};
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) out[static_cast<std::size_t>(4 * col + row)] = static_cast<float>(m[col][row]);
    return out;
}

// The shortest text that reads back as the same double.
std::string shortest(double v) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
    return std::string(buffer, end);
}

}  // namespace

ExrCameraMatrices exrCameraMatrices(const CameraFrame& camera, const Projection& projection) {
    // Camera axes in OpenEXR's order: e2 is image right, e1 up, e3 the view (docs of CameraFrame).
    const glm::dvec3 axes[3] = {camera.e2, camera.e1, camera.e3};
    glm::dmat4 to_camera(1.0);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) to_camera[c][r] = axes[r][c];
        to_camera[3][r] = -glm::dot(axes[r], camera.position);
    }
    // Raster x = W/2 + (x/z) k and y = H/2 - (y/z) k with k = H / (2 tan(vfov/2)) (Projection); NDC is
    // raster over (W, H). Homogeneous rows: x' = sx x + z/2, y' = -sy y + z/2, z' = 1, w = z.
    const double sy = 0.5 / projection.tan_half_vfov;
    const double sx = sy * projection.height / projection.width;
    glm::dmat4 to_ndc(0.0);
    to_ndc[0][0] = sx;
    to_ndc[2][0] = 0.5;
    to_ndc[1][1] = -sy;
    to_ndc[2][1] = 0.5;
    to_ndc[3][2] = 1.0;
    to_ndc[2][3] = 1.0;
    return {toExr(to_camera), toExr(to_ndc * to_camera)};
}

std::array<int, 2> fpsRational(double fps) {
    for (int denominator : {1, 1001}) {
        const double numerator = std::round(fps * denominator);
        if (std::abs(numerator / denominator - fps) <= 1e-9 * fps) return {static_cast<int>(numerator), denominator};
    }
    // fps is in [1e-3, 1e4] (schema), so thousandths give a numerator in [1, 1e7]: no overflow.
    const int denominator = 1000;
    const int numerator = static_cast<int>(std::lround(fps * denominator));
    const int g = std::gcd(numerator, denominator);
    return {numerator / g, denominator / g};
}

FrameHeader frameHeader(const RenderJob& job, int frame) {
    FrameHeader h;
    h.frame = frame;
    const std::array<int, 2> fps = fpsRational(job.frames.fps);
    h.fps_numerator = fps[0];
    h.fps_denominator = fps[1];
    h.shutter_open = job.shutter.open;
    h.shutter_close = job.shutter.close;
    h.exposure_seconds = (job.shutter.close - job.shutter.open) / job.frames.fps;
    for (const ShutterPoint& p : job.shutter.curve) {
        if (!h.shutter_curve.empty()) h.shutter_curve += ' ';
        h.shutter_curve += shortest(p.time) + ':' + shortest(p.weight);
    }
    const Scene& scene = job.scene;
    const ExrCameraMatrices m = exrCameraMatrices(evalCamera(scene.camera, frame + job.shutter.open),
                                                  Projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees));
    h.world_to_camera = m.world_to_camera;
    h.world_to_ndc = m.world_to_ndc;
    return h;
}

}  // namespace clipblur
