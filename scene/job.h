#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/pixel_bounds.h"
#include "scene/scene.h"

namespace clipblur {

enum class Method { Clipped, Stochastic, Accumulation, Frame0Only };
enum class PathMethod { Exact, Euler, RK4 };
enum class TimeIntegration { Subframes, Sweep, Auto };
// How sweep integrates time between re-clips: Points places each fragment at positions sweep_spacing
// pixels of travel apart; Exact integrates its coverage exactly along chords through positions spaced by
// how far paths bend (renderer/geometry/chord_sweep.h).
enum class SweepTime { Points, Exact };
// How a clipped fragment piece gets its one colour: shaded at its area centroid with an image texture
// filtered over the whole piece (Centroid), or cut into a fan of triangles about the centroid, each shaded
// that way, their colours averaged by area (Fan: as many shading points as the piece has vertices), or
// shaded at its centroid with an image texture's bilinear image integrated exactly over the piece's
// preimage in (s, t) (Integral).
enum class FragmentShading { Centroid, Fan, Integral };

// The name a job file uses for the method.
const char* methodName(Method method);

// A point of the shutter curve: a time (frames, relative to the frame, as open and close) and the
// shutter's relative weight there.
struct ShutterPoint {
    double time = 0.0;
    double weight = 1.0;
};

// Frame k's shutter spans [k + open, k + close]: -1 <= open <= close <= 1 and close - open <= 1, so a
// centred shutter (-0.25 .. 0.25) opens before its frame. `curve` is empty (a box) or runs from open
// to close with increasing times and weights >= 0, not all zero (ShutterCurve normalises it).
struct Shutter {
    double open = 0.0;
    double close = 1.0;
    std::vector<ShutterPoint> curve;
};

struct FrameRange {
    int first = 0;
    int last = 0;
    double fps = 24.0;
};

struct RenderSettings {
    Method method = Method::Clipped;
    int samples = 16;          // stochastic: samples per pixel; accumulation: renders per frame
    int subframes = 0;         // clipped: 0 means automatic (paper eq. 24)
    int max_subframes = 256;
    int segments = 0;          // clipped: shutter segments with their own fragment sets; 0 means auto
    int max_segments = 32;
    PathMethod path_method = PathMethod::Exact;
    int ode_steps = 16;        // per subframe interval, Euler and RK4 only
    // Subframes: the paper's point samples, every subframe re-clipped. Sweep: a subframe's re-clipped
    // fragments also stand for the rest of its interval, each moved along its own displacement to
    // positions sweep_spacing pixels apart, so visibility is re-clipped far less often than a pixel:
    // automatic re-clips follow relative motion, sweep_spacing (or reclip_spacing) pixels of it apart.
    // Auto: per shutter segment the cheaper of the two at equal spacing (point subframes then put
    // vertices sweep_spacing pixels apart; renderer/clipped/integration_cost.h).
    TimeIntegration time_integration = TimeIntegration::Auto;
    double sweep_spacing = 1.0;
    // Sweep: pixels of relative motion between automatic re-clips (their path tolerances scale with it as
    // with sweep_spacing); 0 follows sweep_spacing.
    double reclip_spacing = 0.0;
    SweepTime sweep_time = SweepTime::Points;
    // Clipped: the RMS time-sampling error (R, G, B, white = 1) to aim for; 0: off. A pilot render
    // measures estimated_error and the spacing (sweep, auto) or subframe count (subframes) is chosen from it
    // (renderer/clipped/error_target.h).
    double error_target = 0.0;
    FragmentShading fragment_shading = FragmentShading::Integral;
    int visibility_rays = 2;   // Embree candidate rays per pixel side (n x n per pixel)
    bool shadows = false;

    // Whether any segment may be integrated by sweep: `sweep`, or `auto` without a fixed subframe count
    // (which means point subframes).
    bool maySweep() const {
        return time_integration == TimeIntegration::Sweep || (time_integration == TimeIntegration::Auto && subframes == 0);
    }
    std::uint64_t seed = 0;
    int tile_size = 32;
    // Check every resolved tile's fragments (inside the pixel, disjoint, covering exactly what the inputs
    // cover, nearest surface kept) and fail the render on a violation. Slow; for tests and bug reports.
    bool audit = false;
    // The pixels to compute; unset means the whole film. Not part of the job file (render --tile sets
    // it per shard), so every shard of a frame shares the job's config hash.
    std::optional<PixelBounds> window;
};

// Separate: the EXR holds premultiplied colour of the surfaces only (OpenEXR convention; comp an
// "over" onto any plate). Bake: the film background is composited under it and alpha is 1.
enum class BackgroundMode { Separate, Bake };
enum class ExrCompression { Zip, Piz, Dwaa, None };

// Cryptomatte ID mattes of objects (Psyop's specification 1.1.0): `depth` ranked (ID, coverage) pairs
// per pixel in layers <name>00, <name>01, ... (two pairs each).
struct CryptomatteSettings {
    bool enabled = false;
    std::string name = "CryptoObject";
    int depth = 6;
};

struct OutputSettings {
    std::string path = "render.exr";
    bool half = true;          // R, G, B, A and coverage only; Z and motion are always float
    ExrCompression compression = ExrCompression::Zip;
    BackgroundMode background = BackgroundMode::Separate;
    bool png_preview = false;
    bool aov_depth = false;
    bool aov_coverage = false;
    bool aov_motion = false;
    CryptomatteSettings cryptomatte;
    std::string stats_path;    // empty: beside the image as <image>.stats.json
};

struct RenderJob {
    int version = 1;
    Scene scene;
    Shutter shutter;
    FrameRange frames;
    RenderSettings render;
    OutputSettings output;
    std::string source_file;
    std::string config_hash;   // hash of the resolved config, for EXR metadata
    std::vector<std::string> warnings;  // found while loading (degenerate triangles, camera inside an object)
};

}  // namespace clipblur
