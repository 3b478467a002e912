#include "renderer/clipped/motion_plan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>

#include "renderer/parallel_time.h"
#include "renderer/propagation/group_parallax.h"
#include "renderer/thread_scratch.h"
#include "scene/error.h"
#include "scene/object_motion.h"

namespace clipblur {

namespace {

// Whether the fragment triangles of backdrop objects can be taken out of `refs`: every moving one stays
// nearer than all of them over the segment (depth is affine over a fragment, so its vertices' depth range
// bounds every point). What moves in front then only changes how much of the backdrop each pixel
// sees, which the swept coverage gives: no re-clip needs to follow it. A moving fragment reaching the
// camera plane has no bounded path, so it keeps the tile as it is.
template <class ObjectOf>
bool splitsBackdrop(std::span<const FragmentRef> refs, const std::array<std::vector<FragmentMotion>, 2>& motion,
                    const std::vector<char>& backdrop_objects, ObjectOf object) {
    double moving_far = -std::numeric_limits<double>::infinity(), still_near = std::numeric_limits<double>::infinity();
    bool moving = false, still = false;
    for (const FragmentRef& ref : refs) {
        const FragmentMotion& fm = motion[ref.layer()][ref.index()];
        if (backdrop_objects[object(ref)]) {
            still = true;
            still_near = std::min(still_near, fm.min_depth);
        } else {
            if (fm.crosses_near) return false;
            moving = true;
            moving_far = std::max(moving_far, fm.max_depth);
        }
    }
    return moving && still && moving_far < still_near;
}

// A box holding fm.displacementNear(x) for every x in `box`: the displacement is affine in x, so on the
// source triangle it lies within its corners' values, and without one within the box's corners' values.
// Padded well beyond the rounding of those evaluations (1e-12 of raster coordinates), so that pairs
// skipped by it (relativeMotion) could not have raised the maximum.
RasterBounds displacementRange(const FragmentMotion& fm, const RasterBounds& box) {
    RasterBounds range;
    if (fm.has_source) {
        for (const glm::dvec2& corner : fm.source_open) range.expand(fm.displacement(corner));
    } else {
        for (const glm::dvec2& corner : {box.lo, box.hi, glm::dvec2(box.lo.x, box.hi.y), glm::dvec2(box.hi.x, box.lo.y)})
            range.expand(fm.displacement(corner));
    }
    range.pad(1e-6 * (1.0 + std::max({std::abs(range.lo.x), std::abs(range.lo.y), std::abs(range.hi.x), std::abs(range.hi.y)})));
    return range;
}

// The largest distance between a point of a and a point of b.
double farthestApart(const RasterBounds& a, const RasterBounds& b) {
    return glm::length(glm::max(a.hi - b.lo, b.hi - a.lo));
}

// How far surfaces move relative to each other where they can meet in `tile` (eq. 24's pixel rule, for
// what one hides of another): for every two fragment triangles whose swept boxes overlap within the
// tile, at the overlap's corners. Of different motion groups (`group`): the largest difference of their
// open-to-close displacements, each taken at the point of its source triangle nearest to the corner
// (FragmentMotion::displacementNear): on the triangle the map is affine and within its corners' exact
// displacements, beyond it an extrapolation, which reached 6000 px at a sphere's silhouette
// (configs/default.yaml at 64x36: every tile capped at 256 re-clips). Surfaces that cross in mid-segment
// count though they are apart at both ends. The pairs come from a sweep along x over the boxes sorted by
// their left edge; a tile with one group has none (slidingWithin measures what moves inside a group).
template <class GroupOf>
double relativeMotion(std::span<const FragmentRef> refs, const std::array<std::vector<FragmentMotion>, 2>& motion,
                      const RasterBounds& tile, GroupOf group) {
    struct Item {
        RasterBounds box;  // swept box within the tile
        std::uint32_t group;
        const FragmentMotion* motion;
        RasterBounds reach;  // holds displacementNear of every point of box (displacementRange)
    };
    struct Scratch {
        std::vector<Item> items;
        std::vector<const Item*> active;
    };
    auto& [items, active] = threadScratch<Scratch>();
    items.clear();
    bool several = false;
    for (const FragmentRef& ref : refs) {
        const FragmentMotion& fm = motion[ref.layer()][ref.index()];
        if (fm.crosses_near) continue;
        const RasterBounds box{glm::max(fm.swept.lo, tile.lo), glm::min(fm.swept.hi, tile.hi)};
        if (box.empty()) continue;
        items.push_back({box, group(ref), &fm, displacementRange(fm, box)});
        several = several || items.back().group != items.front().group;
    }
    if (!several) return 0.0;
    std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.box.lo.x < b.box.lo.x; });
    double relative = 0.0;  // a max: the same whatever order ties are in
    active.clear();
    for (const Item& item : items) {
        std::erase_if(active, [&](const Item* a) { return a->box.hi.x < item.box.lo.x; });
        for (const Item* other : active) {
            if (other->group == item.group) continue;
            const RasterBounds meet{glm::max(item.box.lo, other->box.lo), glm::min(item.box.hi, other->box.hi)};
            if (meet.empty() || farthestApart(item.reach, other->reach) <= relative) continue;
            for (const glm::dvec2& corner :
                 {meet.lo, meet.hi, glm::dvec2(meet.lo.x, meet.hi.y), glm::dvec2(meet.hi.x, meet.lo.y)})
                relative = std::max(relative, glm::length(item.motion->displacementNear(corner) -
                                                          other->motion->displacementNear(corner)));
        }
        active.push_back(&item);
    }
    return relative;
}

// How far surfaces of one motion group slide over each other in `tile` when the eye moves relative to
// the group (GroupParallax). Only surfaces one behind the other can change what one hides of the other:
// at each of kSlideSamples x kSlideSamples points spread over the tile, the nearest and farthest of the
// group's source triangles over the point at open (every fragment triangle's, so what either end set saw
// near there), and their parallax. Points along one ray part monotonically as their inverse depths do,
// so no two surfaces there part further. One plane (a floor cut into triangles) has one depth at a
// point, and a convex object's faces seen at an end do not overlap: neither slides.
constexpr int kSlideSamples = 5;

template <class GroupOf>
double slidingWithin(std::span<const FragmentRef> refs, const std::array<std::vector<FragmentMotion>, 2>& motion,
                     const RasterBounds& tile, GroupOf group, const GroupParallax& parallax) {
    constexpr int kPoints = kSlideSamples * kSlideSamples;
    struct Depths {
        std::uint32_t group;
        std::array<double, kPoints> nearest, farthest;
    };
    std::vector<Depths>& groups = threadScratch<std::vector<Depths>>();
    groups.clear();
    const glm::dvec2 step = (tile.hi - tile.lo) / double(kSlideSamples - 1);
    const auto point = [&](int k) { return tile.lo + step * glm::dvec2(k % kSlideSamples, k / kSlideSamples); };
    for (const FragmentRef& ref : refs) {
        const FragmentMotion& fm = motion[ref.layer()][ref.index()];
        const std::uint32_t g = group(ref);
        if (fm.crosses_near || !fm.has_source || !parallax.slides(g)) continue;
        auto depths = std::find_if(groups.begin(), groups.end(), [&](const Depths& d) { return d.group == g; });
        for (int k = 0; k < kPoints; ++k) {
            const std::optional<double> w = fm.inverseDepthAt(point(k));
            if (!w) continue;
            if (depths == groups.end()) {
                depths = groups.insert(groups.end(), Depths{g, {}, {}});
                depths->nearest.fill(0.0);
                depths->farthest.fill(std::numeric_limits<double>::infinity());
            }
            depths->nearest[static_cast<std::size_t>(k)] = std::max(depths->nearest[static_cast<std::size_t>(k)], *w);
            depths->farthest[static_cast<std::size_t>(k)] = std::min(depths->farthest[static_cast<std::size_t>(k)], *w);
        }
    }
    double sliding = 0.0;
    for (const Depths& d : groups)
        for (int k = 0; k < kPoints; ++k) {
            const auto i = static_cast<std::size_t>(k);
            if (d.nearest[i] > d.farthest[i]) sliding = std::max(sliding, parallax.between(d.group, point(k), d.nearest[i], d.farthest[i]));
        }
    return sliding;
}

// The pixels of `tile` a re-clip of `refs` resolves, for the cost of one (integrationCost): each fragment
// triangle's area at open shared out over its swept box by how much of the box lies in the tile, summed,
// at most the tile's area. Backdrop fragments split off (splitsBackdrop) are not in refs.
double resolvedPixels(std::span<const FragmentRef> refs, const FragmentPaths& paths, const PixelBounds& tile) {
    const double tile_area = static_cast<double>(tile.area());
    double covered = 0.0;
    for (const FragmentRef& ref : refs) {
        const FragmentMotion& fm = paths.motion[ref.layer()][ref.index()];
        const double area = paths.area[ref.layer()][ref.index()];
        if (fm.crosses_near || !std::isfinite(area)) return tile_area;
        const glm::dvec2 size = fm.swept.hi - fm.swept.lo;
        const glm::dvec2 lo = glm::max(fm.swept.lo, glm::dvec2(tile.x0, tile.y0)),
                         hi = glm::min(fm.swept.hi, glm::dvec2(tile.x1, tile.y1));
        const glm::dvec2 inside = glm::max(hi - lo, glm::dvec2(0.0));
        const double box = size.x * size.y;
        covered += box > 0.0 ? area * (inside.x * inside.y) / box : 0.0;
        if (covered >= tile_area) return tile_area;
    }
    return covered;
}

}  // namespace

TileBins::TileBins(const TileGrid& grid, const std::array<std::vector<FragmentMotion>, 2>& motion) {
    for (const auto& m : motion)
        if (m.size() >= std::size_t{1} << 31) throw Error(ExitCode::Render, "a fragment set of 2^31 triangles or more");
    const double size = grid.tileSize();
    // Calls f(tile, ref) for every tile each fragment's swept box overlaps, in ref order (a fragment
    // reaching the camera plane may have the whole plane as its box: every tile).
    const auto forEachBin = [&](auto&& f) {
        for (std::uint8_t layer = 0; layer < 2; ++layer) {
            const auto& m = motion[layer];
            for (std::uint32_t i = 0; i < m.size(); ++i) {
                const RasterBounds& box = m[i].swept;
                const int c0 = static_cast<int>(std::clamp(std::floor(box.lo.x / size), 0.0, double(grid.columns())));
                const int c1 = static_cast<int>(std::clamp(std::floor(box.hi.x / size), -1.0, double(grid.columns() - 1)));
                const int r0 = static_cast<int>(std::clamp(std::floor(box.lo.y / size), 0.0, double(grid.rows())));
                const int r1 = static_cast<int>(std::clamp(std::floor(box.hi.y / size), -1.0, double(grid.rows() - 1)));
                for (int r = r0; r <= r1; ++r)
                    for (int c = c0; c <= c1; ++c) f(static_cast<std::size_t>(r * grid.columns() + c), FragmentRef{i, layer});
            }
        }
    };
    begin_.assign(static_cast<std::size_t>(grid.count()) + 1, 0);
    forEachBin([&](std::size_t tile, FragmentRef) { ++begin_[tile + 1]; });
    std::partial_sum(begin_.begin(), begin_.end(), begin_.begin());
    refs_.resize(begin_.back());
    std::vector<std::size_t> next(begin_.begin(), begin_.end() - 1);
    forEachBin([&](std::size_t tile, FragmentRef ref) { refs_[next[tile]++] = ref; });
}

FragmentPaths measurePaths(const FrameSetup& frame, const MotionWindow& window, const FragmentLayers& layers) {
    const Scene& scene = frame.scene();
    const Projection& projection = frame.projection;
    // Few intervals: the swept box keeps a speed-times-gap margin, and the count uses peak speed.
    const ShutterPathSampler sampler(scene, projection, window.t0, window.t1, 2);
    const MotionSnapshot open(scene, projection, window.t0);

    FragmentPaths paths;
    for (int layer = 0; layer < 2; ++layer) {
        const auto* triangles = layers.triangles[static_cast<std::size_t>(layer)];
        if (!triangles) continue;
        auto& m = paths.motion[static_cast<std::size_t>(layer)];
        auto& area = paths.area[static_cast<std::size_t>(layer)];
        m.resize(triangles->size());
        area.resize(triangles->size());
        parallelFor(std::size_t(0), triangles->size(), [&](std::size_t i) {
            const FragmentTriangle& t = (*triangles)[i];
            const std::array<MeshPoint, 3> points{MeshPoint{t.object, t.triangle, t.bary[0]},
                                                  MeshPoint{t.object, t.triangle, t.bary[1]},
                                                  MeshPoint{t.object, t.triangle, t.bary[2]}};
            std::array<ProjectedPoint, 3> q;
            for (int v = 0; v < 3; ++v) q[static_cast<std::size_t>(v)] = project(open, scene, points[static_cast<std::size_t>(v)]);
            const glm::dvec2 e1 = q[1].raster - q[0].raster, e2 = q[2].raster - q[0].raster;
            // A vertex behind the camera: no bounded image, so as if it covered everything it reaches.
            area[i] = q[0].behind || q[1].behind || q[2].behind ? std::numeric_limits<double>::infinity()
                                                               : 0.5 * std::abs(e1.x * e2.y - e1.y * e2.x);
            if (window.stillInImage(t.object)) {
                FragmentMotion fm;
                for (const ProjectedPoint& p : q) {
                    fm.swept.expand(p.raster);
                    fm.start += p.raster / 3.0;
                    fm.min_depth = std::min(fm.min_depth, p.depth);
                    fm.max_depth = std::max(fm.max_depth, p.depth);
                }
                fm.end = fm.start;
                m[i] = fm;
            } else {
                m[i] = sampler.measure(points);
            }
        });
        for (std::size_t i = 0; i < triangles->size(); ++i) paths.measured += window.stillInImage((*triangles)[i].object) ? 0 : 1;
    }
    paths.bins = std::make_shared<const TileBins>(frame.grid, paths.motion);
    return paths;
}

MotionPlan planMotion(const FrameSetup& frame, const MotionWindow& window, const FragmentLayers& layers,
                      const FragmentPaths& paths, const MotionPlanOptions& options) {
    const TileGrid& grid = frame.grid;
    const int subframes = options.subframes, max_subframes = options.max_subframes;
    const bool sweep = options.sweep;
    const Backdrop& backdrop = options.backdrop;
    const std::array<std::vector<FragmentMotion>, 2>& motion = paths.motion;
    MotionPlan plan;
    plan.measured = paths.measured;

    const int count = grid.count();
    plan.bins = paths.bins;
    plan.backdrop.resize(static_cast<std::size_t>(count));
    plan.resolved.resize(static_cast<std::size_t>(count));
    plan.tiles.resize(static_cast<std::size_t>(count));
    for (const auto& m : motion)
        for (const FragmentMotion& fm : m) plan.near_crossings += fm.crosses_near ? 1 : 0;

    const auto object = [&](const FragmentRef& ref) { return (*layers.triangles[ref.layer()])[ref.index()].object; };
    // Relative motion is between surfaces that move differently in the world, not between objects: a
    // surface cut into many objects that move together has none, as one object has none with itself.
    plan.groups = frame.motion.groups(window);
    const auto motionGroup = [&](const FragmentRef& ref) { return plan.groups[object(ref)]; };
    const GroupParallax parallax(frame.motion, frame.projection, window, plan.groups);
    if (sweep && !backdrop.empty() && !backdrop.behind_everything) plan.front.resize(static_cast<std::size_t>(count));
    parallelFor(0, count, [&](int index) {
        const auto t = static_cast<std::size_t>(index);
        if (sweep && !backdrop.empty()) {
            const std::span<const FragmentRef> all = (*plan.bins)[index];
            plan.backdrop[t] = backdrop.behind_everything || splitsBackdrop(all, motion, backdrop.objects, object);
            if (plan.backdrop[t] && !backdrop.behind_everything)
                std::copy_if(all.begin(), all.end(), std::back_inserter(plan.front[t]),
                             [&](const FragmentRef& ref) { return backdrop.objects[object(ref)] == 0; });
        }
        const std::span<const FragmentRef> refs = plan.refs(index);
        SubframePlan& p = plan.tiles[static_cast<std::size_t>(index)];
        p = SubframePlan{};
        plan.resolved[static_cast<std::size_t>(index)] = resolvedPixels(refs, paths, grid.tile(index));
        for (const FragmentRef& ref : refs) {
            const FragmentMotion& fm = motion[ref.layer()][ref.index()];
            ++p.fragments;
            // A fragment reaching the camera plane has unbounded image speed there: no subframe count
            // resolves it, and letting it set the count would cap every tile it may touch (all of them).
            // It is still re-clipped (cut in 3D at the plane) at the subframes the rest of the tile needs.
            if (fm.crosses_near) {
                ++p.near_crossings;
                continue;
            }
            p.max_path_pixels = std::max(p.max_path_pixels, fm.max_path_pixels);
            p.max_sweep_pixels = std::max(p.max_sweep_pixels, fm.max_sweep_pixels);
        }
        if (subframes > 0) {
            p.count = std::min(subframes, max_subframes);
        } else if (!sweep) {
            p.count = subframeCount(kinkSamples(p.max_sweep_pixels, options.shutter_share, options.point_spacing),
                                    max_subframes, &p.capped);
        } else {
            // Sweep integration moves each fragment along its own path between re-clips, so what one
            // surface does smoothly (a pan, a roll, a dolly) needs no re-clip. Re-clips follow what is
            // left: how far surfaces of different motion groups move relative to each other (what one
            // hides of another: at most reclip_spacing pixels per re-clip, eq. 24 at that spacing), and
            // how far a path leaves the parabola a sweep follows (its distance from the parabola through
            // its positions at the segment's ends and middle: third order, falling as the cube of the count).
            // Inside one group, what the eye's motion relative to it slides over what (parallax).
            constexpr double kChordTolerance = 0.1;  // px at reclip_spacing 1, scaled with it (below)
            // Fragments move rigidly along their centroid's path, stretched along the raster axes as the
            // surface is (SweepPath); a surface that turns or shears under them (a roll) is followed to
            // within FragmentMotion::unstretched_error / n with n intervals, kept at kChordTolerance.
            // Each fragment triangle's own open-to-close map gives it.
            double deviation = 0.0, unstretched = 0.0;
            for (const FragmentRef& ref : refs) {
                const FragmentMotion& fm = motion[ref.layer()][ref.index()];
                if (fm.crosses_near) continue;
                deviation = std::max(deviation, fm.parabola_deviation);
                unstretched = std::max(unstretched, fm.unstretched_error);
            }
            const PixelBounds t = grid.tile(index);
            const RasterBounds box{{t.x0, t.y0}, {t.x1, t.y1}};
            const double relative = std::max(relativeMotion(refs, motion, box, motionGroup),
                                             slidingWithin(refs, motion, box, motionGroup, parallax));
            // A fragment off its path by d px is a first-order error in d, while positions r px apart
            // leave an error of order r^2 below a pixel (midpoint rule) and r above: the tolerance follows
            // the positions' order, so re-clips do not set the error at fine spacings.
            const double r = options.reclip_spacing, tolerance = kChordTolerance * r * std::min(r, 1.0);
            p.count = subframeCount(std::max({relative / r, std::cbrt(deviation / tolerance), unstretched / tolerance}),
                                    max_subframes, &p.capped);
        }
    });
    // Sweep integration carries fragments across tile borders during an interval, so every moving tile
    // must share the intervals (different ones would count a border-crossing surface twice or not at all).
    if (sweep) {
        int shared = 1;
        bool capped = false;
        for (const SubframePlan& p : plan.tiles)
            if (p.max_sweep_pixels > 0.0) {
                shared = std::max(shared, p.count);
                capped = capped || p.capped;
            }
        for (SubframePlan& p : plan.tiles) {
            p.count = shared;
            p.capped = capped && p.max_sweep_pixels > 0.0;
        }
    }
    for (const SubframePlan& p : plan.tiles) plan.capped_tiles += p.capped ? 1 : 0;
    for (const char b : plan.backdrop) plan.backdrop_tiles += b ? 1 : 0;
    return plan;
}

}  // namespace clipblur
