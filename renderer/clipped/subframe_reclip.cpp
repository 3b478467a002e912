#include "renderer/clipped/subframe_reclip.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "renderer/check.h"
#include "renderer/clipped/time_error.h"
#include "renderer/visibility/frame_geometry.h"

namespace clipblur {

namespace {

// Moves fragment triangle `ref` to the re-clip's time and adds it to the screen triangles, weighted by its
// layer's share (frame 0: 1 - f, frame 1: f); pieces behind the camera plane are cut off in 3D, where
// barycentrics interpolate linearly, so the kept part still knows its surface points.
void propagate(const TileReclip& tile, const ReclipTime& at, FragmentRef ref, ReclipScratch& scratch,
               ReclipStats& stats) {
    const MotionSnapshot& snapshot = at.snapshot;
    const OdePropagator* ode = tile.layers.ode;
    const FragmentTriangle& t = (*tile.layers.triangles[ref.layer()])[ref.index()];
    const float weight = static_cast<float>(ref.layer() == 0 ? 1.0 - at.fraction : at.fraction);
    const auto add = [&](const std::array<glm::dvec3, 3>& world, const SourceTriangle& source) {
        ScreenTriangle s;
        for (int i = 0; i < 3; ++i) {
            const ImagePoint ip = projectToImagePlane(snapshot.camera, world[i]);
            s.raster[i] = snapshot.projection.toRaster(ip.p);
            s.inv_depth[i] = 1.0 / ip.depth;
        }
        s.source = static_cast<std::uint32_t>(scratch.screen.size());
        s.layer = ref.layer();
        s.weight = weight;
        s.surface = std::uint64_t(source.object) << 32 | source.triangle;
        scratch.screen.push_back(s);
        scratch.origin.push_back(ref);
        scratch.sources.push_back(source);
    };
    std::array<glm::dvec3, 3> world;
    bool behind = false;
    for (int i = 0; i < 3; ++i) {
        const MeshPoint point{t.object, t.triangle, t.bary[i]};
        std::optional<glm::dvec3> moved;
        if (ode) {
            moved = ode->propagate(point, ref.layer(), snapshot.time);
            if (!moved) ++stats.ode_fallbacks;
        }
        if (moved) {
            world[i] = *moved;
            behind = behind || glm::dot(snapshot.camera.e3, world[i] - snapshot.camera.position) < kNearDepth;
        } else {
            const ProjectedPoint p = project(snapshot, tile.scene, point);
            world[i] = p.world;
            behind = behind || p.behind || p.depth < kNearDepth;
        }
    }
    // Scene validation keeps every key finite, so the exact paths are; the ODE falls back before it diverges.
    CLIPBLUR_DCHECK(std::isfinite(world[0].x + world[0].y + world[0].z + world[1].x + world[1].y + world[1].z +
                                  world[2].x + world[2].y + world[2].z));
    ++stats.propagated;
    if (!behind) {
        add(world, {t.object, t.triangle, t.bary});
        return;
    }
    ++stats.near_clipped;
    const NearClipped c = clipToNearPlane(snapshot.camera, kNearDepth, world, t.bary);
    const int n = c.count;
    const auto& w = c.world;
    const auto& b = c.bary;
    if (n >= 3) add({w[0], w[1], w[2]}, {t.object, t.triangle, {b[0], b[1], b[2]}});
    if (n == 4) add({w[0], w[2], w[3]}, {t.object, t.triangle, {b[0], b[2], b[3]}});
}

// The surface point that `sample` (a point of a screen triangle) finds on the source's mesh triangle.
MeshPoint meshPointOf(const SourceTriangle& source, const SourceSample& sample) {
    glm::dvec3 bary(0.0);
    for (int i = 0; i < 3; ++i) bary += sample.bary[i] * source.bary[i];
    return {source.object, source.triangle, bary};
}

// The motion AOV: how far the surface point of screen triangle s at raster point `at` moves from
// shutter open to close; 0 where it is behind the camera at either.
glm::dvec2 surfaceMotion(const TileReclip& tile, const ReclipScratch& scratch, std::uint32_t s, const glm::dvec2& at) {
    SourceSample sample;
    if (!evalSource(scratch.screen[s], at, sample)) return glm::dvec2(0.0);
    const MeshPoint point = meshPointOf(scratch.sources[s], sample);
    const ProjectedPoint a = project(*tile.layers.shutter[0], tile.scene, point),
                         b = project(*tile.layers.shutter[1], tile.scene, point);
    return a.behind || b.behind ? glm::dvec2(0.0) : b.raster - a.raster;
}

// The path of the surface point seen at the fragment's centroid `at` over the interval: through its exact
// positions and depths at the interval's ends and `at` itself (sample: the centroid on the source screen
// triangle). Nullopt when the point is behind the camera at either end.
std::optional<SweepPath> sweepPath(const Scene& scene, const SweepInterval& sweep, const SourceTriangle& source,
                                   const SourceSample& sample, const glm::dvec2& at) {
    const MeshPoint point = meshPointOf(source, sample);
    const ProjectedPoint a = project(*sweep.begin, scene, point), b = project(*sweep.end, scene, point);
    if (a.behind || b.behind) return std::nullopt;
    if (!sweep.turns) return SweepPath::through({a.raster, a.depth}, {at, 1.0 / sample.inv_depth}, {b.raster, b.depth});
    SweepPath path = SweepPath::through({a.raster, a.depth}, {at, 1.0 / sample.inv_depth}, {b.raster, b.depth},
                                        sweep.turns->unturn_begin, sweep.turns->unturn_end);
    path.turns = sweep.turns->at_positions;
    return path;
}

// How much the surface under a screen triangle stretches along each raster axis at the interval's start
// and end: the lengths of the images of the unit x and y vectors under the affine map that carries the
// triangle's vertices from t to there, negative along an axis the surface turns away in (the sweep then
// skips the positions where it faces away). Rotation and shear are left to the rigid move (their error is
// what the re-clip count bounds); identity where a vertex is behind the camera or the triangle is a sliver.
glm::dvec4 surfaceStretch(const Scene& scene, const SweepInterval& sweep, const ScreenTriangle& screen,
                          const SourceTriangle& source) {
    const glm::dvec2 e1 = screen.raster[1] - screen.raster[0], e2 = screen.raster[2] - screen.raster[0];
    const double det = e1.x * e2.y - e1.y * e2.x;
    const glm::dvec4 identity(1.0);
    if (!(std::abs(det) > 1e-9 * (glm::dot(e1, e1) + glm::dot(e2, e2)))) return identity;
    const glm::dmat2 from_t = glm::inverse(glm::dmat2(e1, e2));
    glm::dvec4 stretch;
    int k = 0;
    for (const MotionSnapshot* snapshot : {sweep.begin, sweep.end}) {
        std::array<glm::dvec2, 3> r;
        for (int i = 0; i < 3; ++i) {
            const ProjectedPoint p = project(*snapshot, scene, {source.object, source.triangle, source.bary[i]});
            if (p.behind) return identity;
            r[i] = p.raster;
        }
        const glm::dmat2 map = glm::dmat2(r[1] - r[0], r[2] - r[0]) * from_t;
        stretch[k++] = signedStretch(map, 0);
        stretch[k++] = signedStretch(map, 1);
    }
    return stretch;
}

// Adds a piece's colour difference, merged into an equal piece already listed (both frames' copies of
// a surface are usually cut along the same texture edges).
void addTextured(const ConvexPolygon& piece, const glm::dvec3& colour,
                 std::vector<std::pair<ConvexPolygon, glm::dvec3>>& textured) {
    for (auto& [polygon, c] : textured) {
        if (polygon.n == piece.n && std::equal(piece.v.begin(), piece.v.begin() + piece.n, polygon.v.begin())) {
            c += colour;
            return;
        }
    }
    textured.push_back({piece, colour});
}

// One re-clip's state across the pixels of its region.
struct ReclipPass {
    const TileReclip& tile;
    const ReclipTime& at;
    ReclipScratch& scratch;
    TileSums& out;
    ReclipStats& stats;
};

// A resolved fragment, shaded: its polygon, its colour and motion per px^2 (its sources mixed), its
// objects' shares, and its first source's surface sampled at its centroid. With a sweep, a textured
// fragment's pieces other than the largest go to scratch.textured as colour differences.
struct ShadedFragment {
    ConvexPolygon polygon;
    glm::dvec3 colour{0.0};
    glm::dvec2 motion{0.0};
    PolygonObjects objects;
    glm::dvec2 centroid{0.0};
    std::uint32_t first = 0;  // the first source's screen triangle
    SourceSample sample;
    bool sampled = false;      // the centroid lies on the first source, in front of the camera
    double inv_depth = 0.0;    // 0 when not sampled
};

// Screen triangle s's shading, set up when a fragment of it is first shaded in this re-clip.
const TriangleShading& shadingOf(ReclipScratch& scratch, std::uint32_t s, const Shader& shader) {
    std::int32_t& slot = scratch.shading_slot[s];
    if (slot < 0) {
        slot = static_cast<std::int32_t>(scratch.shading.size());
        scratch.shading.emplace_back(FragmentSurface{scratch.screen[s], scratch.sources[s]}, shader);
    }
    return scratch.shading[static_cast<std::size_t>(slot)];
}

ShadedFragment shadeResolved(ReclipPass& pass, const Fragment& fragment) {
    ++pass.stats.fragments;
    if (fragment.source_count > 1) ++pass.stats.mixed;
    ReclipScratch& scratch = pass.scratch;
    ShadedFragment shaded;
    ConvexPolygon& polygon = shaded.polygon;
    for (int k = 0; k < fragment.vertex_count; ++k) polygon.push(fragment.vertices[k]);
    polygon.close();
    scratch.textured.clear();
    // Every piece is shaded where its surface is at the re-clip's time, lit and seen as it is then: the
    // frames' colours mixed in proportion to time would follow lighting that changes during the shutter
    // (a face turning under a light, a limb bending) only along a chord, an error no re-clip removes.
    const ShadingFrame now{pass.at.snapshot.time, pass.at.snapshot.camera.position};
    // So both frames' copies of one triangle shade alike: one shading serves the pair, the mix weights
    // summing to 1.
    const auto shadeOnce = [&] {
        const SourceTriangle& a = scratch.sources[fragment.sources[0].source];
        const SourceTriangle& b = scratch.sources[fragment.sources[1].source];
        return a.object == b.object && a.triangle == b.triangle;
    };
    const bool shade_once = fragment.source_count == 2 && shadeOnce();
    shaded.centroid = centroid(polygon);
    for (int k = 0; pass.out.track_objects && k < fragment.source_count; ++k)
        shaded.objects.add(static_cast<int>(scratch.sources[fragment.sources[k].source].object), fragment.mix(k));
    for (int k = 0; k < fragment.source_count; ++k) {
        const std::uint32_t s = fragment.sources[k].source;
        if (pass.tile.layers.shutter[0]) shaded.motion += fragment.mix(k) * surfaceMotion(pass.tile, scratch, s, shaded.centroid);
        if (shade_once && k == 1) continue;
        const double m = shade_once ? 1.0 : fragment.mix(k);
        scratch.pieces.clear();
        shadingOf(scratch, s, pass.tile.shader).shade(polygon, now, scratch.pieces);
        pass.stats.shaded_pieces += static_cast<long long>(scratch.pieces.size());
        glm::dvec3 sum(0.0);
        double area = 0.0;
        for (const ShadedPiece& piece : scratch.pieces) {
            sum += piece.area * piece.colour;
            area += piece.area;
        }
        if (pass.at.sweep && scratch.pieces.size() > 1 && area > 0.0) {
            // Swept pieces keep their own colours: the fragment's mean colour smeared over pixels would
            // move a texture edge inside it to the fragment's centre. Footprints add up over pieces, so
            // the whole fragment carries the largest piece's colour and the other pieces only their
            // difference to it.
            const double scale = m * fragment.area / area;
            const auto base = std::max_element(scratch.pieces.begin(), scratch.pieces.end(),
                                               [](const auto& a, const auto& b) { return a.area < b.area; });
            shaded.colour += scale * base->colour;
            for (auto piece = scratch.pieces.begin(); piece != scratch.pieces.end(); ++piece)
                if (piece != base) addTextured(piece->polygon, scale * (piece->colour - base->colour), scratch.textured);
        } else if (area > 0.0) {
            shaded.colour += m * sum / area;
        }
    }
    shaded.first = fragment.sources[0].source;
    shaded.sampled = evalSource(scratch.screen[shaded.first], shaded.centroid, shaded.sample) && shaded.sample.inv_depth > 0.0;
    shaded.inv_depth = shaded.sampled ? shaded.sample.inv_depth : 0.0;
    return shaded;
}

// A point re-clip: the fragment's area and what it carries go to its own pixel.
void addPoint(ReclipPass& pass, const ShadedFragment& shaded, std::size_t i, double area) {
    TileSums& out = pass.out;
    out.colour[i] += area * shaded.colour;
    out.covered[i] += area;
    out.motion[i] += area * shaded.motion;
    if (shaded.inv_depth > 0.0) out.depth[i] += area / shaded.inv_depth;
    for (int k = 0; k < shaded.objects.count; ++k)
        addShare(out.objects[i], shaded.objects.shares[static_cast<std::size_t>(k)].object,
                 area * shaded.objects.shares[static_cast<std::size_t>(k)].coverage);
}

// The motion groups of one pixel's swept fragments: whether all are swept and of one group, so that
// they move alike and can be merged (mergePixel).
struct PixelSurface {
    bool one = true;
    std::uint32_t group = std::numeric_limits<std::uint32_t>::max();
};

// A sweep re-clip: queues the fragment (and its texture pieces) to be swept along the path of the
// surface point under its centroid; a path reaching past the interval's reach stays a point sample.
void queueSwept(ReclipPass& pass, const Fragment& fragment, const ShadedFragment& shaded, PixelSurface& surface) {
    const SweepInterval& sweep = *pass.at.sweep;
    ReclipScratch& scratch = pass.scratch;
    const Scene& scene = pass.tile.scene;
    std::optional<SweepPath> path = shaded.sampled ? sweepPath(scene, sweep, scratch.sources[shaded.first],
                                                               shaded.sample, shaded.centroid)
                                                   : std::nullopt;
    if (path) {
        glm::dvec4& stretch = scratch.stretch[shaded.first];
        if (std::isnan(stretch.x))
            stretch = surfaceStretch(scene, sweep, scratch.screen[shaded.first], scratch.sources[shaded.first]);
        path->setStretch(glm::dvec2(stretch.x, stretch.y), glm::dvec2(stretch.z, stretch.w));
    }
    int positions = 1;
    SweepPath shift;
    if (path && sweep.sweeps(*path)) {
        shift = *path;
        shift.tilt = sweep.tilt;
        if (shift.moves()) positions = sweep.positions;
    } else {
        ++pass.stats.sweep_unswept;
        surface.one = false;
    }
    for (int k = 0; k < fragment.source_count; ++k) {
        const std::uint32_t group = sweep.groups[scratch.sources[fragment.sources[k].source].object];
        if (surface.group == std::numeric_limits<std::uint32_t>::max()) surface.group = group;
        surface.one = surface.one && group == surface.group;
    }
    SweptPolygon swept;
    swept.polygon = shaded.polygon;
    swept.path = shift;
    swept.positions = positions;
    swept.colour = shaded.colour;
    swept.motion = shaded.motion;
    swept.depth = shaded.sampled ? 1.0 / shaded.inv_depth : 0.0;
    swept.objects = shaded.objects;
    scratch.swept.push_back(swept);  // swept after the tile's last fragment: only then is the box known
    for (const auto& [piece, piece_colour] : scratch.textured) {
        SweptPolygon difference;
        difference.polygon = piece;
        difference.path = shift;
        difference.positions = positions;
        difference.colour = piece_colour;
        difference.coverage = false;
        scratch.swept.push_back(difference);
    }
}

// Moves every fragment triangle that can reach the tile to the re-clip's time and resolves the pixels to
// re-clip into non-overlapping fragments (scratch.fragments); returns those pixels: the tile, or with a
// sweep its resolve box.
PixelBounds resolveRegion(ReclipPass& pass) {
    ReclipScratch& scratch = pass.scratch;
    scratch.screen.clear();
    scratch.origin.clear();
    scratch.sources.clear();
    for (const FragmentRef ref : pass.tile.refs) propagate(pass.tile, pass.at, ref, scratch, pass.stats);
    scratch.shading_slot.assign(scratch.screen.size(), -1);
    scratch.shading.clear();
    const PixelBounds region = pass.at.sweep ? pass.at.sweep->resolve : pass.tile.tile;
    resolveTile(scratch.screen, region, {}, scratch.tile, scratch.fragments);
    if (pass.tile.audit) auditTile(scratch.screen, scratch.fragments, pass.stats.audit);
    return region;
}

// A point re-clip: each fragment, shaded, adds to its own pixel.
void pointRegion(ReclipPass& pass, const PixelBounds& region) {
    pass.out.reset(pass.tile.tile);
    for (int y = region.y0; y < region.y1; ++y)
        for (int x = region.x0; x < region.x1; ++x)
            for (const Fragment& fragment : pass.scratch.fragments.pixel(x, y))
                addPoint(pass, shadeResolved(pass, fragment), pass.out.box.index(x, y), fragment.area);
}

// A sweep re-clip: each fragment, shaded, is queued with its path (a pixel's fragments merged into one
// rectangle where they move as one, mergePixel), then all are swept into the tile's sums.
void sweepRegion(ReclipPass& pass, const PixelBounds& region) {
    ReclipScratch& scratch = pass.scratch;
    // Each screen triangle's stretch, computed when a fragment first needs it (NaN: not yet).
    scratch.stretch.assign(scratch.screen.size(), glm::dvec4(std::numeric_limits<double>::quiet_NaN()));
    scratch.swept.clear();
    for (int y = region.y0; y < region.y1; ++y) {
        for (int x = region.x0; x < region.x1; ++x) {
            const std::size_t pixel_begin = scratch.swept.size();
            PixelSurface surface;
            for (const Fragment& fragment : scratch.fragments.pixel(x, y))
                queueSwept(pass, fragment, shadeResolved(pass, fragment), surface);
            if (surface.one) mergePixel(scratch.swept, pixel_begin, scratch.staging);
            for (std::size_t i = pixel_begin; i < scratch.swept.size(); ++i)
                if (scratch.swept[i].coverage) pass.stats.sweep_positions += scratch.swept[i].positions;
        }
    }
    accumulateSwept(*pass.at.sweep, pass.tile.tile, scratch.swept, pass.out);
}

}  // namespace

void reclipSubframe(const TileReclip& tile, const ReclipTime& at, ReclipScratch& scratch, TileSums& out,
                    ReclipStats& stats) {
    ReclipPass pass{tile, at, scratch, out, stats};
    const PixelBounds region = resolveRegion(pass);
    if (at.sweep)
        sweepRegion(pass, region);
    else
        pointRegion(pass, region);
}

}  // namespace clipblur
