#include "renderer/clipped/frame_fragments.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <span>

#include <tbb/enumerable_thread_specific.h>

#include "renderer/fragments/fragment_tile.h"
#include "renderer/parallel_time.h"
#include "renderer/shading/fragment_shading.h"
#include "renderer/visibility/frame_geometry.h"
#include "scene/error.h"

namespace clipblur {

// Each array first touched (page faults) on a task of its own.
void PixelSums::resize(std::size_t pixels, bool with_objects) {
    parallelInvoke([&] { colour.assign(pixels, glm::dvec3(0.0)); }, [&] { covered.assign(pixels, 0.0); },
                   [&] { depth.assign(pixels, 0.0); }, [&] { objects.assign(with_objects ? pixels : 0, {}); });
}

namespace {

int bucketOf(std::size_t count) {
    if (count <= 2) return static_cast<int>(count);
    if (count <= 4) return 3;
    return count <= 8 ? 4 : 5;
}

// The part of a screen triangle inside the tile's rectangle.
ConvexPolygon clipToTile(const ScreenTriangle& t, const PixelBounds& tile) {
    ConvexPolygon poly = ConvexPolygon::triangle(t.raster[0], t.raster[1], t.raster[2]);
    const double bounds[4] = {double(tile.x0), double(tile.x1), double(tile.y0), double(tile.y1)};
    for (int side = 0; side < 4; ++side) {
        std::array<double, kMaxPolygonVertices> s{};
        const int axis = side / 2;
        const double sign = side % 2 == 0 ? 1.0 : -1.0;
        for (int k = 0; k < poly.n; ++k) s[static_cast<std::size_t>(k)] = sign * (poly.v[k][axis] - bounds[side]);
        ConvexPolygon inside;
        clipByValues(poly, s.data(), inside);
        poly = inside;
        if (poly.degenerate()) break;
    }
    return poly;
}

// Appends a visible convex polygon of `screen` as fragment triangles (a fan) on the mesh triangle.
void emitPolygon(const ConvexPolygon& polygon, const ScreenTriangle& screen, const SourceTriangle& source,
                 std::vector<FragmentTriangle>& out) {
    std::array<glm::dvec3, kMaxPolygonVertices> bary{};
    for (int k = 0; k < polygon.n; ++k) {
        SourceSample s;
        evalSource(screen, polygon.v[k], s);
        bary[static_cast<std::size_t>(k)] = s.bary[0] * source.bary[0] + s.bary[1] * source.bary[1] + s.bary[2] * source.bary[2];
    }
    for (int k = 1; k + 1 < polygon.n; ++k)
        out.push_back({source.object, source.triangle, {bary[0], bary[static_cast<std::size_t>(k)], bary[static_cast<std::size_t>(k + 1)]}});
}

// Where a frame triangle index stands in a tile's candidates (sorted, and holding it).
std::size_t localIndex(const std::vector<std::uint32_t>& candidates, std::uint32_t screen) {
    return static_cast<std::size_t>(std::lower_bound(candidates.begin(), candidates.end(), screen) - candidates.begin());
}

// Whether the pixel's only fragment is the whole pixel square of one source: its four corners exactly.
bool wholePixel(std::span<const Fragment> fragments, int x, int y) {
    if (fragments.size() != 1 || fragments[0].source_count != 1 || fragments[0].vertex_count != 4) return false;
    const glm::dvec2 corners[4] = {{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}};
    for (int k = 0; k < 4; ++k)
        if (std::find(std::begin(corners), std::end(corners), fragments[0].vertices[k]) == std::end(corners)) return false;
    return true;
}

// The tile's whole pixels (wholePixel) of candidates not kept whole, as rectangles: each row's runs of one
// candidate, merged with the run of the row above that spans the same columns. Emitted as fragment
// triangles in place of a pair per pixel (the interior of a partly hidden wall becomes a few
// rectangles); `done` marks their pixels. The output depends only on the tile's fragments.
void emitWholeRectangles(const FragmentTile& fragments, const std::vector<std::uint32_t>& candidates,
                         const std::vector<char>& merged, const FrameGeometry& frame, std::vector<char>& done,
                         std::vector<FragmentTriangle>& out) {
    const PixelBounds& tile = fragments.rect;
    struct Rectangle {
        int x0, x1, y0, y1;
        std::uint32_t screen;  // the frame's triangle index
    };
    std::vector<Rectangle> open, next;
    const auto emit = [&](const Rectangle& r) {
        ConvexPolygon polygon;
        for (const glm::dvec2& p : {glm::dvec2(r.x0, r.y0), glm::dvec2(r.x1, r.y0), glm::dvec2(r.x1, r.y1), glm::dvec2(r.x0, r.y1)})
            polygon.push(p);
        emitPolygon(polygon, frame.triangles()[r.screen], frame.source(r.screen), out);
    };
    const auto wholeOf = [&](int x, int y, std::uint32_t& screen) {
        const auto pixel = fragments.pixel(x, y);
        if (!wholePixel(pixel, x, y)) return false;
        screen = pixel[0].sources[0].source;
        return merged[localIndex(candidates, screen)] == 0;
    };
    done.assign(tile.area(), 0);
    for (int y = tile.y0; y < tile.y1; ++y) {
        next.clear();
        for (int x = tile.x0; x < tile.x1;) {
            std::uint32_t screen = 0, other = 0;
            if (!wholeOf(x, y, screen)) {
                ++x;
                continue;
            }
            int end = x + 1;
            while (end < tile.x1 && wholeOf(end, y, other) && other == screen) ++end;
            for (int k = x; k < end; ++k) done[tile.index(k, y)] = 1;
            const auto above = std::find_if(open.begin(), open.end(), [&](const Rectangle& r) {
                return r.x0 == x && r.x1 == end && r.screen == screen;
            });
            next.push_back({x, end, above != open.end() ? above->y0 : y, y + 1, screen});
            if (above != open.end()) open.erase(above);
            x = end;
        }
        for (const Rectangle& r : open) emit(r);
        open.swap(next);
    }
    for (const Rectangle& r : open) emit(r);
}

struct TileOutput {
    std::vector<FragmentTriangle> triangles;
    FrameFragmentStats stats;
};

}  // namespace

void FrameFragmentStats::merge(const FrameFragmentStats& s) {
    candidates.rays += s.candidates.rays;
    candidates.hit_triangles += s.candidates.hit_triangles;
    candidates.candidates += s.candidates.candidates;
    candidates.binned += s.candidates.binned;
    candidates.exhaustive_tiles += s.candidates.exhaustive_tiles;
    fragments += s.fragments;
    shaded_pieces += s.shaded_pieces;
    merged_triangles += s.merged_triangles;
    triangles += s.triangles;
    near_clipped += s.near_clipped;
    deep_tiles += s.deep_tiles;
    rejected_triangles += s.rejected_triangles;
    dropped_area += s.dropped_area;
    for (std::size_t b = 0; b < s.fragments_per_pixel.size(); ++b) fragments_per_pixel[b] += s.fragments_per_pixel[b];
    audit.merge(s.audit);
}

std::vector<FragmentTriangle> buildFrameFragments(const FrameSetup& setup, const FrameFragmentRequest& request,
                                                  PixelSums* still, FrameFragmentStats& stats) {
    const Scene& scene = setup.scene();
    const TileGrid& grid = request.grid ? *request.grid : setup.grid;
    const double time = request.time;
    const RenderCallbacks& callbacks = setup.callbacks;
    const FrameGeometry frame(setup.motion, setup.projection, time, grid);
    const glm::dvec3 eye = frame.camera().position;
    const int width = scene.film.width;
    const int height = scene.film.height;
    std::vector<TileOutput> outputs(static_cast<std::size_t>(grid.count()));
    std::atomic<bool> cancelled{false};

    // Scratch per thread, reused by its tiles (cleared on every use; nothing here starts TBB work).
    struct Scratch {
        CandidateScratch candidates;
        TileScratch tile;
        FragmentTile fragments;  // a tile's pieces: kept, as fresh pages for each tile cost page faults
    };
    tbb::enumerable_thread_specific<Scratch> scratches;
    parallelFor(0, grid.count(), [&](int index) {
        if (callbacks.cancel && callbacks.cancel->load(std::memory_order_relaxed)) {
            cancelled = true;
            return;
        }
        const PixelBounds tile = grid.tile(index);
        TileOutput& out = outputs[static_cast<std::size_t>(index)];
        Scratch& scratch = scratches.local();
        const bool deep = request.deep && request.deep->contains(index);
        std::vector<std::uint32_t> candidates =
            findCandidates(frame, {setup.embree, setup.adjacency, deep ? 0 : request.rays_per_side}, index, scratch.candidates,
                           out.stats.candidates);
        if (request.leave_out)
            std::erase_if(candidates, [&](std::uint32_t c) { return (*request.leave_out)[frame.source(c).object] != 0; });
        std::vector<ScreenTriangle> local;
        local.reserve(candidates.size());
        for (std::uint32_t c : candidates) local.push_back(frame.triangles()[c]);

        FragmentTile& fragments = scratch.fragments;
        resolveTile(local, tile, {}, scratch.tile, fragments);
        out.stats.rejected_triangles += fragments.rejected_triangles;
        out.stats.dropped_area += fragments.dropped_area;
        if (request.audit) auditTile(local, fragments, out.stats.audit);

        // Visible area of each candidate in the tile. A triangle whose visible area is all of its part
        // inside the tile is kept as that one polygon instead of one piece per pixel: same surface points,
        // far fewer triangles to propagate and re-clip (a large floor triangle becomes one, not hundreds).
        std::vector<double> visible(candidates.size(), 0.0);
        for (const Fragment& fragment : fragments.fragments) visible[localIndex(candidates, fragment.sources[0].source)] += fragment.area;
        // A deep tile keeps every candidate's part in it, seen or hidden, so each counts as merged.
        std::vector<char> merged(candidates.size(), deep ? 1 : 0);
        out.stats.deep_tiles += deep ? 1 : 0;
        for (std::size_t c = 0; c < candidates.size(); ++c) {
            if (!deep && visible[c] <= 0.0) continue;
            const ScreenTriangle& screen = frame.triangles()[candidates[c]];
            const ConvexPolygon part = clipToTile(screen, tile);
            if (part.degenerate()) continue;
            if (!deep) {
                // Relative slack for the rounding of summed pixel pieces; a real occlusion of 1e-9 of a
                // triangle's area inside one tile is far below what any pixel can show.
                if (visible[c] < std::abs(part.area()) * (1.0 - 1e-9)) continue;
                merged[c] = 1;
                ++out.stats.merged_triangles;
            }
            emitPolygon(part, screen, frame.source(candidates[c]), out.triangles);
        }

        std::vector<char> whole;
        emitWholeRectangles(fragments, candidates, merged, frame, whole, out.triangles);

        std::vector<ShadedPiece> pieces;
        for (int y = tile.y0; y < tile.y1; ++y) {
            for (int x = tile.x0; x < tile.x1; ++x) {
                const auto pixel_fragments = fragments.pixel(x, y);
                ++out.stats.fragments_per_pixel[static_cast<std::size_t>(bucketOf(pixel_fragments.size()))];
                out.stats.fragments += static_cast<long long>(pixel_fragments.size());
                const std::size_t pixel = static_cast<std::size_t>(std::max(y, 0)) * width + std::max(x, 0);
                for (const Fragment& fragment : pixel_fragments) {
                    const std::uint32_t screen_index = fragment.sources[0].source;  // the frame's triangle index
                    const ScreenTriangle& screen = frame.triangles()[screen_index];
                    const SourceTriangle& source = frame.source(screen_index);
                    ConvexPolygon polygon;
                    for (int k = 0; k < fragment.vertex_count; ++k) polygon.push(fragment.vertices[k]);
                    polygon.close();
                    if (!merged[localIndex(candidates, screen_index)] && !whole[tile.index(x, y)])
                        emitPolygon(polygon, screen, source, out.triangles);
                    if (!still || x < 0 || y < 0 || x >= width || y >= height) continue;  // guard band
                    pieces.clear();
                    shadeFragment(polygon, {screen, source}, setup.shader, {time, eye}, pieces);
                    out.stats.shaded_pieces += static_cast<long long>(pieces.size());
                    for (const ShadedPiece& piece : pieces) {
                        still->colour[pixel] += piece.area * piece.colour;
                        still->covered[pixel] += piece.area;
                        if (!still->objects.empty())
                            addShare(still->objects[pixel], static_cast<int>(source.object), piece.area);
                        SourceSample s;
                        if (evalSource(screen, centroid(piece.polygon), s)) still->depth[pixel] += piece.area / s.inv_depth;
                    }
                }
            }
        }
        out.stats.triangles = static_cast<long long>(out.triangles.size());
        if (!request.keep_triangles) out.triangles.clear();
    });
    if (cancelled) throw Error(ExitCode::Interrupted, "render cancelled");

    std::vector<FragmentTriangle> all;
    stats.near_clipped += frame.clippedByNearPlane();
    std::size_t total = 0;
    for (const TileOutput& out : outputs) total += out.triangles.size();
    all.reserve(total);  // exactly: growing by doubling would hold up to twice the set
    for (TileOutput& out : outputs) {
        all.insert(all.end(), out.triangles.begin(), out.triangles.end());
        std::vector<FragmentTriangle>().swap(out.triangles);
        stats.merge(out.stats);
    }
    return all;
}

}  // namespace clipblur
