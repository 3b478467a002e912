#include "renderer/clipped/subframe_reclip.h"

#include "renderer/visibility/frame_geometry.h"

namespace clipblur {

void TileSums::reset(std::size_t pixels) {
    colour.assign(pixels, glm::dvec3(0.0));
    covered.assign(pixels, 0.0);
    depth.assign(pixels, 0.0);
    motion.assign(pixels, glm::dvec2(0.0));
}

namespace {

void addScreenTriangle(const MotionSnapshot& snapshot, const std::array<glm::dvec3, 3>& world,
                       const SourceTriangle& source, FragmentRef ref, float weight, ReclipScratch& scratch) {
    ScreenTriangle s;
    for (int i = 0; i < 3; ++i) {
        const ImagePoint ip = projectToImagePlane(snapshot.camera, world[i]);
        s.raster[i] = snapshot.projection.toRaster(ip.p);
        s.inv_depth[i] = 1.0 / ip.depth;
    }
    s.source = static_cast<std::uint32_t>(scratch.screen.size());
    s.layer = ref.layer;
    s.weight = weight;
    scratch.screen.push_back(s);
    scratch.origin.push_back(ref);
    scratch.sources.push_back(source);
}

// Moves one fragment triangle to the snapshot's time; pieces behind the camera plane are cut off in 3D,
// where barycentrics interpolate linearly, so the kept part still knows its surface points.
void propagate(const Scene& scene, const MotionSnapshot& snapshot, const OdePropagator* ode,
               const FragmentTriangle& t, FragmentRef ref, float weight, ReclipScratch& scratch, ReclipStats& stats) {
    std::array<glm::dvec3, 3> world;
    bool behind = false;
    for (int i = 0; i < 3; ++i) {
        const MeshPoint point{t.object, t.triangle, t.bary[i]};
        std::optional<glm::dvec3> moved;
        if (ode) {
            moved = ode->propagate(point, ref.layer, snapshot.time);
            if (!moved) ++stats.ode_fallbacks;
        }
        if (moved) {
            world[i] = *moved;
            behind = behind || glm::dot(snapshot.camera.e3, world[i] - snapshot.camera.position) < kNearDepth;
        } else {
            const ProjectedPoint p = project(snapshot, scene, point);
            world[i] = p.world;
            behind = behind || p.behind || p.depth < kNearDepth;
        }
    }
    ++stats.propagated;
    if (!behind) {
        addScreenTriangle(snapshot, world, {t.object, t.triangle, t.bary}, ref, weight, scratch);
        return;
    }
    ++stats.near_clipped;
    std::array<glm::dvec3, 4> w, b;
    const int n = clipToNearPlane(snapshot.camera, kNearDepth, world, t.bary, w, b);
    if (n >= 3) addScreenTriangle(snapshot, {w[0], w[1], w[2]}, {t.object, t.triangle, {b[0], b[1], b[2]}}, ref, weight, scratch);
    if (n == 4) addScreenTriangle(snapshot, {w[0], w[2], w[3]}, {t.object, t.triangle, {b[0], b[2], b[3]}}, ref, weight, scratch);
}

}  // namespace

void reclipSubframe(const Scene& scene, const Shader& shader, const MotionSnapshot& snapshot, double f,
                    const FragmentLayers& layers, std::span<const FragmentRef> refs, const Tile& tile,
                    bool audit, ReclipScratch& scratch, TileSums& out, ReclipStats& stats) {
    scratch.screen.clear();
    scratch.origin.clear();
    scratch.sources.clear();
    const std::array<float, 2> weights{static_cast<float>(1.0 - f), static_cast<float>(f)};
    for (const FragmentRef ref : refs)
        propagate(scene, snapshot, layers.ode, (*layers.triangles[ref.layer])[ref.index], ref, weights[ref.layer],
                  scratch, stats);

    resolveTile(scratch.screen, {tile.x0, tile.y0, tile.width(), tile.height()}, {}, scratch.tile, scratch.fragments);
    if (audit) auditTile(scratch.screen, scratch.fragments, stats.audit);
    const std::size_t pixels = static_cast<std::size_t>(tile.width()) * tile.height();
    out.reset(pixels);
    for (int y = tile.y0; y < tile.y1; ++y) {
        for (int x = tile.x0; x < tile.x1; ++x) {
            const std::size_t i = static_cast<std::size_t>(y - tile.y0) * tile.width() + (x - tile.x0);
            for (const Fragment& fragment : scratch.fragments.pixel(x, y)) {
                ++stats.fragments;
                if (fragment.source_count > 1) ++stats.mixed;
                ConvexPolygon polygon;
                for (int k = 0; k < fragment.vertex_count; ++k) polygon.push(fragment.vertices[k]);
                polygon.close();
                glm::dvec3 colour(0.0);
                glm::dvec2 motion(0.0);
                for (int k = 0; k < fragment.source_count; ++k) {
                    const std::uint32_t s = fragment.sources[k].source;
                    const FragmentRef ref = scratch.origin[s];
                    const double m = fragment.mix(k);
                    // The piece is where this source's surface is now; it is shaded as its frame saw it.
                    scratch.pieces.clear();
                    shadeFragment(polygon, scratch.screen[s], scratch.sources[s], shader, layers.time[ref.layer],
                                  layers.eye[ref.layer], scratch.pieces);
                    stats.shaded_pieces += static_cast<long long>(scratch.pieces.size());
                    glm::dvec3 sum(0.0);
                    double area = 0.0;
                    for (const ShadedPiece& piece : scratch.pieces) {
                        sum += piece.area * piece.colour;
                        area += piece.area;
                    }
                    if (area > 0.0) colour += m * sum / area;
                    if (!layers.motion[ref.layer].empty()) motion += m * glm::dvec2(layers.motion[ref.layer][ref.index]);
                }
                out.colour[i] += fragment.area * colour;
                out.covered[i] += fragment.area;
                out.motion[i] += fragment.area * motion;
                SourceSample sample;
                if (evalSource(scratch.screen[fragment.sources[0].source], centroid(polygon), sample) && sample.inv_depth > 0.0)
                    out.depth[i] += fragment.area / sample.inv_depth;
            }
        }
    }
}

}  // namespace clipblur
