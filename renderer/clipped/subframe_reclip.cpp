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

void addScreenTriangle(const MotionSnapshot& snapshot, const std::array<glm::dvec3, 3>& world, FragmentRef ref,
                       float weight, ReclipScratch& scratch) {
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
}

}  // namespace

void reclipSubframe(const Scene& scene, const MotionSnapshot& snapshot, double f, const FragmentLayers& layers,
                    std::span<const FragmentRef> refs, const Tile& tile, ReclipScratch& scratch, TileSums& out,
                    ReclipStats& stats) {
    scratch.screen.clear();
    scratch.origin.clear();
    const std::array<float, 2> weights{static_cast<float>(1.0 - f), static_cast<float>(f)};
    for (const FragmentRef ref : refs) {
        const FragmentTriangle& t = (*layers.triangles[ref.layer])[ref.index];
        std::array<ProjectedPoint, 3> p;
        bool behind = false;
        for (int i = 0; i < 3; ++i) {
            p[i] = project(snapshot, scene, MeshPoint{t.object, t.triangle, t.bary[i]});
            behind = behind || p[i].behind || p[i].depth < kNearDepth;
        }
        ++stats.propagated;
        if (!behind) {
            ScreenTriangle s;
            for (int i = 0; i < 3; ++i) {
                s.raster[i] = p[i].raster;
                s.inv_depth[i] = p[i].inv_depth;
            }
            s.source = static_cast<std::uint32_t>(scratch.screen.size());
            s.layer = ref.layer;
            s.weight = weights[ref.layer];
            scratch.screen.push_back(s);
            scratch.origin.push_back(ref);
            continue;
        }
        ++stats.near_clipped;
        const std::array<glm::dvec3, 3> world{p[0].world, p[1].world, p[2].world};
        const std::array<glm::dvec3, 3> unused{};
        std::array<glm::dvec3, 4> w, b;
        const int n = clipToNearPlane(snapshot.camera, kNearDepth, world, unused, w, b);
        if (n >= 3) addScreenTriangle(snapshot, {w[0], w[1], w[2]}, ref, weights[ref.layer], scratch);
        if (n == 4) addScreenTriangle(snapshot, {w[0], w[2], w[3]}, ref, weights[ref.layer], scratch);
    }

    resolveTile(scratch.screen, {tile.x0, tile.y0, tile.width(), tile.height()}, {}, scratch.tile, scratch.fragments);
    const std::size_t pixels = static_cast<std::size_t>(tile.width()) * tile.height();
    out.reset(pixels);
    for (int y = tile.y0; y < tile.y1; ++y) {
        for (int x = tile.x0; x < tile.x1; ++x) {
            const std::size_t i = static_cast<std::size_t>(y - tile.y0) * tile.width() + (x - tile.x0);
            for (const Fragment& fragment : scratch.fragments.pixel(x, y)) {
                ++stats.fragments;
                if (fragment.source_count > 1) ++stats.mixed;
                glm::dvec3 colour(0.0);
                glm::dvec2 motion(0.0);
                for (int k = 0; k < fragment.source_count; ++k) {
                    const FragmentRef ref = scratch.origin[fragment.sources[k].source];
                    const double m = fragment.mix(k);
                    colour += m * glm::dvec3((*layers.triangles[ref.layer])[ref.index].colour);
                    if (!layers.motion[ref.layer].empty()) motion += m * glm::dvec2(layers.motion[ref.layer][ref.index]);
                }
                out.colour[i] += fragment.area * colour;
                out.covered[i] += fragment.area;
                out.motion[i] += fragment.area * motion;
                SourceSample s;
                const ScreenTriangle& screen = scratch.screen[fragment.sources[0].source];
                glm::dvec2 mean(0.0);
                for (int k = 0; k < fragment.vertex_count; ++k) mean += fragment.vertices[k];
                if (evalSource(screen, mean / double(fragment.vertex_count), s) && s.inv_depth > 0.0)
                    out.depth[i] += fragment.area / s.inv_depth;
            }
        }
    }
}

}  // namespace clipblur
