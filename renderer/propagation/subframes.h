#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/geometry/closest_point.h"
#include "renderer/geometry/raster_bounds.h"
#include "renderer/propagation/surface_path.h"
#include "scene/scene.h"

namespace clipblur {

// How one fragment (a convex polygon of surface points) moves over the shutter.
struct FragmentMotion {
    RasterBounds swept;                // conservative bound of every raster position the fragment takes on the image
    double max_path_pixels = 0.0;   // longest raster path of a vertex over the shutter, on the image
    // Peak raster speed of any vertex times the shutter length: equal subframes of this many keep every
    // vertex within a pixel per step. It is never below max_path_pixels and equals it for uniform speed.
    double max_sweep_pixels = 0.0;
    // A vertex reaches the camera plane: its image speed is unbounded, and swept is the whole plane, or
    // for straight paths the image of what of its swept hull is in front (ShutterPathSampler::measure).
    bool crosses_near = false;
    glm::dvec2 start{0.0}, end{0.0};  // mean raster position of the vertices at shutter open and close
    // Largest distance of a sampled vertex position from the path a sweep with one interval follows
    // (SweepPath::through its positions and depths at open, mid-shutter and close): a third-order error,
    // so for smooth paths it falls as the cube of the interval count; 0 for paths under translation alone.
    double parabola_deviation = 0.0;
    // What a sweep with one interval, which moves a fragment along its centre's path and stretches it
    // along the raster axes (S, the lengths of the columns of the affine map J carrying the triangle's
    // vertices from open to close) without turning it, misses of the triangle's motion: how far a
    // fragment's vertex strays at the interval's ends, the largest |(J - S) e| / |e| x (half of |e|, at
    // most half a pixel's diagonal: a fragment is a piece of the triangle within one pixel) / 2, in
    // pixels. 0 for a sliver or when a vertex reaches the camera plane.
    double unstretched_error = 0.0;
    // The open-to-close affine map of the whole source triangle the fragment is a piece of (clipped
    // pieces are often slivers, whose own map is ill-posed): the surface point at raster x at open is near
    // end + open_to_close (x - start) at close, exactly for motion that is affine in the image. The
    // identity when the source triangle is seen edge-on or reaches the camera plane.
    glm::dmat2 open_to_close{1.0};
    // That source triangle's corners at open (raster), when open_to_close was fitted to them. Outside
    // the triangle its map is an extrapolation, and for a nearly edge-on face (a sphere's silhouette) one
    // of thousands of pixels: displacementNear stays on the triangle.
    std::array<glm::dvec2, 3> source_open{};
    // Its inverse camera depths at those corners: inverse depth is affine over a plane's image.
    std::array<double, 3> source_open_inv_depth{};
    bool has_source = false;
    // Range of the vertices' depth over the shutter, padded by (largest sampled depth rate) x (largest gap
    // between samples) as the swept box is. Depth is affine over a planar fragment, so every point of it
    // stays within this range: what decides whether one surface stays in front of another.
    double min_depth = std::numeric_limits<double>::infinity();
    double max_depth = -std::numeric_limits<double>::infinity();

    // How far the surface point at raster x at open moves by close, as open_to_close has it.
    glm::dvec2 displacement(const glm::dvec2& x) const { return end + open_to_close * (x - start) - x; }
    // The displacement of the source triangle's point nearest to x: on the triangle the map interpolates
    // its corners' exact displacements, so this stays within their range wherever x is.
    glm::dvec2 displacementNear(const glm::dvec2& x) const {
        return displacement(has_source ? closestPointInTriangle(source_open, x) : x);
    }
    // The source triangle's inverse depth at raster x at open, when x is on it (has_source only).
    std::optional<double> inverseDepthAt(const glm::dvec2& x) const;
};

// Samples the exact vertex paths over the shutter [t0, t1]. The shutter is cut at every camera,
// transform and deformation key inside it (velocity is only piecewise smooth), each piece into
// `intervals_per_piece` equal intervals, and each interval gets a 3-point Gauss-Legendre rule for the
// path length and its end points for the swept box. Snapshots are built once here and shared by every
// fragment measured.
class ShutterPathSampler {
public:
    ShutterPathSampler(const Scene& scene, const Projection& projection, double t0, double t1,
                       int intervals_per_piece = 8);

    // Path length in pixels: integral of |d raster/dt| over the shutter. Parts of the path at or behind
    // the near depth are left out (the point is not on the image there).
    double pathLength(const MeshPoint& point) const;

    // Path lengths, peak speeds and swept box of a fragment's vertices, where it is on the image (onFilm:
    // off it no pixel sees the fragment, which near the camera can move thousands of pixels per shutter
    // there). Speeds are taken at the Gauss nodes, which lie strictly inside the pieces (at a key the
    // velocity jumps, and at t1 it may already belong to motion after the shutter). The box holds every
    // sampled position on the image padded by (largest sampled speed there) x (largest gap between
    // samples): the exact path stays inside as long as the speed varies by less than a factor of two
    // between neighbouring samples.
    FragmentMotion measure(std::span<const MeshPoint> vertices) const;

    const std::vector<double>& breakpoints() const { return breakpoints_; }  // t0, keys inside, t1
    bool isBreakpoint(double t) const { return std::binary_search(breakpoints_.begin(), breakpoints_.end(), t); }

    // Whether every surface point of the object moves on a straight image line over the shutter, so that
    // measure takes its paths from their ends alone: one piece (no key inside), a camera that does not
    // turn and moves on a line, and an object that translates on a line without turning, scaling or
    // deforming. Its camera-space position is then linear in time.
    bool straight(std::uint32_t object) const { return straight_[object] != 0; }

private:
    // FragmentMotion::open_to_close of point's triangle, and its corners at open (source_open).
    // With `corners` (cornersOf), projects the corners from them.
    void sourceMap(const MeshPoint& point, FragmentMotion& out,
                   const std::vector<std::array<CameraRelative, 3>>* corners = nullptr) const;
    // A vertex's sampled positions' (raster, depth per node) largest distance from the path a sweep of
    // one interval follows through them and `mid` (FragmentMotion::parabola_deviation).
    double parabolaDeviation(const std::vector<glm::dvec3>& positions, const ProjectedPoint& mid,
                             const std::vector<char>& on_film) const;
    // Per node, whether a fragment whose vertices are at `at` (vertex-major, nodes_.size() per vertex)
    // is on the image (film_); and where it is on the image and how fast its vertices cross its edge.
    struct OnFilm {
        double edge_speed = 0.0;  // peak vertex speed where a vertex crosses the image's edge between nodes
        RasterBounds swept;       // where on the image the fragment can be, unpadded
    };
    OnFilm onFilm(const std::vector<ProjectedMotion>& at, std::size_t vertices, std::vector<char>& on_film) const;
    // measure for vertices on straight paths (straight()); false when a vertex is behind the camera at
    // an end, which the sampled measure handles.
    bool measureStraight(std::span<const MeshPoint> vertices, FragmentMotion& out) const;
    // Where a fragment on straight paths that reaches the camera plane can be on the image.
    RasterBounds crossingBounds(std::span<const MeshPoint> vertices) const;
    // The camera-relative position and rate of point's triangle's corners at every node, then at
    // mid-shutter, from this thread's cache; none when the thread last measured another triangle (or
    // for another sampler), which the next call with this triangle then fills.
    const std::vector<std::array<CameraRelative, 3>>* cornersOf(const MeshPoint& point) const;

    struct Node {
        MotionSnapshot snapshot;
        double weight;  // Gauss-Legendre weight x interval length; 0 for interval end points
    };
    const Scene* scene_;
    std::vector<double> breakpoints_;
    std::vector<Node> nodes_;  // in time order
    MotionSnapshot middle_;    // at (t0 + t1) / 2, for the parabola
    // A turning camera: per node, its turn from middle_ (cameraTurn); and the inverses at the first and
    // last node. Empty when it does not turn.
    std::vector<glm::dmat3> turns_;
    glm::dmat3 unturn_open_{1.0}, unturn_close_{1.0};
    double max_gap_ = 0.0;
    double duration_ = 0.0;
    RasterBounds film_;            // the whole image, raster
    std::vector<char> straight_;  // per object (straight)
    std::uint64_t id_;             // unique per sampler: what a thread's cached corners belong to
};

struct SubframePlan {
    int count = 1;                 // subframes for the tile
    bool capped = false;           // the motion asked for more than max_subframes: caller should warn
    double max_path_pixels = 0.0;  // longest vertex path among the fragments that touch the tile
    double max_sweep_pixels = 0.0; // what the count is made from (see FragmentMotion)
    int fragments = 0;             // fragments whose swept box overlaps the tile
    int near_crossings = 0;        // of those, how many reach the camera plane during the shutter
};

// N = ceil(pixels): at least 1, at most max_subframes (the corrected eq. 24, see docs/errata.md).
int subframeCount(double pixels, int max_subframes, bool* capped = nullptr);

// Point subframes or sweep positions (both midpoint samples in time) for vertices moving `pixels` over an
// interval that holds `share` of the frame's shutter, at `spacing`: what subframeCount takes. Eq. 24's
// pixels / spacing leaves no gaps, but where an edge crosses a pixel the pixel's value kinks in time as
// the edge enters and leaves it, and n midpoint samples err there by up to share pixels / (8 n^2) of the
// edge's contrast: eq. 24 leaves a short motion 1 / (8 pixels), an eighth of the contrast for a motion
// of one pixel, a visible step. So n is at least sqrt(kKinkMotion share pixels) / spacing, which holds
// every motion to the error eq. 24 leaves at kKinkMotion px: 1/512 of the contrast at spacing 1, falling
// as spacing^2, because an 8-bit sRGB display steps up to 12.92x finer than linear near black, where
// 1/256 of a bright edge's contrast showed as 5 code values (docs/performance.md, "Kink floor held to
// the display"). Test: Subframes.KinkSamplesHoldAnEdgeCrossingAPixelToA512thOfItsContrast.
constexpr double kKinkMotion = 64.0;  // px
double kinkSamples(double pixels, double share, double spacing);

// Plans the tile from the fragments whose swept box overlaps it.
SubframePlan planSubframes(std::span<const FragmentMotion> fragments, const RasterBounds& tile, int max_subframes);

// Midpoint rule: subframe k of N at t0 + (k + 1/2)(t1 - t0)/N, each with weight 1/N.
std::vector<double> subframeTimes(double t0, double t1, int count);
inline double subframeWeight(int count) { return 1.0 / count; }

}  // namespace clipblur
