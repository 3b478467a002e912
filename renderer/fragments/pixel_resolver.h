#pragma once

#include <cstdint>
#include <vector>

#include "renderer/fragments/fragment.h"
#include "renderer/fragments/screen_triangle.h"
#include "renderer/geometry/convex_polygon.h"
#include "renderer/geometry/predicates.h"

namespace clipblur {

struct ResolverSettings {
    // Two surfaces coincide over an overlap when |1/z_P - 1/z_Q| <= coincident_rel * max(1/z_P, 1/z_Q) at
    // every vertex of the overlap. Genuinely distinct surfaces that close (1 mm at 1 km) cannot be told
    // apart at image resolution anyway, while the same surface re-projected from frame 0 and from frame 1
    // agrees to rounding (~1e-15) plus the vertex-path error, which the dynamics keep far below 1e-6.
    double coincident_rel = 1e-6;
    // Pieces smaller than this (px^2) are dropped; their area is added to droppedArea(). A 1e-12 px^2 piece
    // is invisible in any colour, and a pixel would need 1e9 such drops to lose 1e-3 of its coverage.
    double min_area = 1e-12;
};

// Coverage a pixel's pieces may miss and still fill it: the cracks rounding leaves along edges that pieces
// share (~1e-15 px^2 each), well below the audit's 1e-9 px^2 per pixel; a real hole is larger.
inline constexpr double kFullPixelSlack = 1e-10;

// Per-pixel hidden-surface resolution into non-overlapping convex fragments.
//
// Triangles are clipped exactly to the pixel and inserted one by one into a set of disjoint convex pieces.
// For a new polygon P against an existing piece Q: P \ Q stays in play against the remaining pieces; in the
// overlap I = P ∩ Q the inverse-depth difference d = 1/z_P - 1/z_Q is affine, so I is cut along d = 0
// (interpenetration): where P is nearer (d > 0) it replaces Q, elsewhere it is dropped. Where d vanishes
// over all of I within tolerance the two are the same surface: from different layers the piece keeps both
// sources (mix); from the same layer the lower source index wins, so results do not depend on insertion
// order. Work happens in pixel-local coordinates (raster minus pixel corner, an exact subtraction), so
// depth planes and areas do not cancel at large raster coordinates. Scratch buffers are members and reused
// across pixels: after warm-up there is no allocation per polygon.
class PixelResolver {
public:
    explicit PixelResolver(ResolverSettings settings = {}) : settings_(settings) {}

    void setSettings(const ResolverSettings& settings) { settings_ = settings; }
    void reset(int px, int py);
    // Ignores (and counts) triangles failing validScreenTriangle. Throws std::invalid_argument for layer > 1.
    void insert(const ScreenTriangle& t);
    // insert for a triangle already validated and clipped to this pixel by its TriangleClipper (`piece`,
    // raster space), with its inverse-depth plane relative to the pixel's corner: what resolveTile does,
    // which clips each triangle's row strip once per row and finds its plane's slopes once.
    void insertClipped(const ScreenTriangle& t, const ConvexPolygon& piece, const DepthPlane& plane);

    // The fragments in raster space; the order is a pure function of the insertion sequence.
    const std::vector<Fragment>& fragments();
    // Appends the same fragments to `out` (what resolveTile collects, without a copy in between).
    void appendFragments(std::vector<Fragment>& out) const;
    double coveredArea() const;
    double droppedArea() const { return dropped_area_.value(); }
    long long rejectedTriangles() const { return rejected_; }

private:
    struct Piece {
        ConvexPolygon poly;  // pixel-local
        RasterBounds box;
        DepthPlane plane;  // pixel-local inverse depth of sources[0]
        double area = 0.0;
        std::array<FragmentSource, 2> sources{};
        std::array<std::uint64_t, 2> surfaces{ScreenTriangle::kNoSurface, ScreenTriangle::kNoSurface};  // per source
        std::uint8_t source_count = 1;
        std::uint32_t epoch = 0;  // insertion that created it; a polygon is never resolved against itself
        bool dead = false;
    };
    struct Work {
        ConvexPolygon poly;
        std::size_t start = 0;  // first piece index not yet resolved against
        double area = kAreaUnknown;
    };
    // For a polygon whose area dropIfSliver has not found yet. Areas passed on are of polygons it kept, so
    // the same polygon is not measured again on its way from clipping to a stored piece.
    static constexpr double kAreaUnknown = -1.0;

    // Inserts mine_'s polygon (pixel-local, of known area) into the pieces.
    void insertPolygon(const ConvexPolygon& local, double area);
    // Whether the pieces fill the pixel and every one lies in front of `plane` over `local`: then the
    // polygon is hidden, which clipping it against each piece would find at greater cost.
    bool hiddenInFullPixel(const ConvexPolygon& local, const DepthPlane& plane) const;
    // Resolves work polygon w (a part of mine_'s) against piece qi; returns false when they do not overlap.
    bool resolve(const ConvexPolygon& w, std::size_t qi);
    // Appends poly (split to stored capacity, slivers dropped) as pieces with the given data.
    void addPiece(const ConvexPolygon& poly, const Piece& data, double area = kAreaUnknown);
    // Replaces piece qi by Q minus w (plus an optional extra part of Q).
    void shrinkPiece(std::size_t qi, const ConvexPolygon& w, const ConvexPolygon* keep);
    void queueWork(const ConvexPolygon& poly, std::size_t start, double area = kAreaUnknown);
    bool dropIfSliver(const ConvexPolygon& poly, double& area);

    ResolverSettings settings_;
    int px_ = 0;
    int py_ = 0;
    std::uint32_t epoch_ = 0;
    Piece mine_;  // the data of the polygon being inserted, given to each piece it leaves
    std::vector<Piece> pieces_;
    std::vector<Work> work_;
    std::vector<Fragment> fragments_;
    bool fragments_valid_ = false;
    CompensatedSum dropped_area_;
    long long rejected_ = 0;
    // Scratch, reused.
    std::vector<ConvexPolygon> outside_;
    std::vector<ConvexPolygon> remnants_;
    std::vector<ConvexPolygon> capped_;
};

}  // namespace clipblur
