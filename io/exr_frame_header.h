#pragma once

#include <array>
#include <string>

#include "scene/camera.h"
#include "scene/job.h"

namespace clipblur {

// A 4x4 matrix in OpenEXR's (Imath's) layout: row-major floats for row vectors, p' = p M.
using ExrMatrix = std::array<float, 16>;

// The standard OpenEXR attributes that describe one frame of a 3D render, plus the frame and shutter.
struct FrameHeader {
    int frame = 0;
    int fps_numerator = 24;    // framesPerSecond is a rational: 24000/1001 stays exact
    int fps_denominator = 1;
    double shutter_open = 0.0;   // frames, relative to the frame number
    double shutter_close = 1.0;
    double exposure_seconds = 0.0;  // expTime: (close - open) / fps
    // The shutter curve as "time:weight" pairs (frames relative to the frame), space-separated; empty
    // for a box, when no attribute is written.
    std::string shutter_curve;
    ExrMatrix world_to_camera{};    // at shutter open
    ExrMatrix world_to_ndc{};       // at shutter open
};

// worldToCamera: OpenEXR's left-handed camera space, x right, y up, z along the view (positive in
// front). worldToNDC: x right, y down, (0, 0) and (1, 1) the display window's upper-left and lower-right
// corners, after the homogeneous divide; its z (1 / depth) is to be discarded.
struct ExrCameraMatrices {
    ExrMatrix world_to_camera{};
    ExrMatrix world_to_ndc{};
};
ExrCameraMatrices exrCameraMatrices(const CameraFrame& camera, const Projection& projection);

// fps as numerator / denominator: exact for integers and NTSC rates (n * 1000 / 1001), else to 1/1000.
std::array<int, 2> fpsRational(double fps);

// The header of frame `frame` of `job`.
FrameHeader frameHeader(const RenderJob& job, int frame);

}  // namespace clipblur
