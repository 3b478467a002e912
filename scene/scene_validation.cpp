#include "scene/scene_validation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/camera.h"
#include "scene/object_motion.h"

namespace clipblur {

namespace {

FileLoc locAt(const std::vector<FileLoc>& locs, std::size_t i, const FileLoc& fallback) {
    return i < locs.size() ? locs[i] : fallback;
}

template <typename T>
const T& itemAt(const std::vector<T>& v, std::size_t i) {
    static const T empty{};
    return i < v.size() ? v[i] : empty;
}

std::string at(const FileLoc& loc) {
    const std::string s = loc.toString();
    return s.empty() ? s : s + ": ";
}

bool sane(double x) { return std::isfinite(x) && std::abs(x) <= kMaxCoordinate; }
bool sane(const glm::dvec3& p) { return sane(p.x) && sane(p.y) && sane(p.z); }

std::string describe(const Object& o, std::size_t index) {
    return "object " + std::to_string(index) + (o.name.empty() ? std::string() : " '" + o.name + "'");
}

template <typename Key>
void requireIncreasing(const std::vector<Key>& keys, const std::vector<FileLoc>& locs, const FileLoc& fallback,
                       const std::string& what) {
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (!std::isfinite(keys[i].time))
            throwSceneError(locAt(locs, i, fallback), what + " key " + std::to_string(i) + " has a non-finite time");
        if (i > 0 && !(keys[i].time > keys[i - 1].time))
            throwSceneError(locAt(locs, i, fallback),
                            what + " keys must be sorted by strictly increasing time: key " + std::to_string(i) +
                                " (time " + std::to_string(keys[i].time) + ") follows time " +
                                std::to_string(keys[i - 1].time));
    }
}

void checkPositions(const std::vector<glm::dvec3>& positions, const FileLoc& loc, const std::string& what) {
    for (std::size_t i = 0; i < positions.size(); ++i) {
        if (!sane(positions[i]))
            throwSceneError(loc, what + ": vertex " + std::to_string(i) +
                                     " has a non-finite or absurd coordinate (|x| > 1e8)");
    }
}

void checkObject(const Object& o, std::size_t index, const Scene& scene, const SceneLocations& locations) {
    const std::string name = describe(o, index);
    if (o.mesh.triangles.empty()) throwSceneError(o.loc, name + " has no triangles");
    checkPositions(o.mesh.positions, o.loc, name);
    const std::size_t n = o.mesh.positions.size();
    for (const auto& t : o.mesh.triangles)
        for (const std::uint32_t v : t)
            if (v >= n)
                throwSceneError(o.loc, name + " has a triangle index " + std::to_string(v) + " beyond its " +
                                           std::to_string(n) + " vertices");
    if (o.material < 0 || static_cast<std::size_t>(o.material) >= scene.materials.size())
        throwSceneError(o.loc, name + " refers to material " + std::to_string(o.material) + " which does not exist");
    const std::size_t corners = 3 * o.mesh.triangles.size();
    if ((o.mesh.smooth() && o.mesh.corner_normals.size() != corners) ||
        (o.mesh.hasUvs() && o.mesh.corner_uvs.size() != corners))
        throwSceneError(o.loc, name + " has corner normals or UVs for other than its " + std::to_string(corners) +
                                   " triangle corners");
    for (const glm::dvec3& normal : o.mesh.corner_normals)
        if (!std::isfinite(normal.x) || !std::isfinite(normal.y) || !std::isfinite(normal.z))
            throwSceneError(o.loc, name + " has a normal that is not finite");
    for (const glm::dvec2& uv : o.mesh.corner_uvs)
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) throwSceneError(o.loc, name + " has a UV that is not finite");
    // Without UVs every point would read the texel at (0, 0): a lost UV export, not a texture.
    const Material& material = scene.materials[static_cast<std::size_t>(o.material)];
    if (!o.mesh.hasUvs() && (!material.image.file.empty() || !material.emission_image.file.empty()))
        throwSceneError(o.loc, name + " has an image texture but no texture coordinates (OBJ 'vt', glTF TEXCOORD_0)");

    const auto& tlocs = itemAt(locations.transform_keys, index);
    requireIncreasing(o.transform, tlocs, o.loc, name + " transform");
    for (std::size_t i = 0; i < o.transform.size(); ++i) {
        const TransformKey& k = o.transform[i];
        const glm::dquat& q = k.rotate;
        const double qn = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
        if (!sane(k.translate) || !sane(k.scale) || !(std::abs(qn - 1.0) < 1e-6))
            throwSceneError(locAt(tlocs, i, o.loc), name + " transform key " + std::to_string(i) +
                                                        " is not finite, absurd, or has a non-unit rotation");
    }

    const auto& dlocs = itemAt(locations.deformation_keys, index);
    requireIncreasing(o.deformation, dlocs, o.loc, name + " deformation");
    for (std::size_t i = 0; i < o.deformation.size(); ++i) {
        const FileLoc loc = locAt(dlocs, i, o.loc);
        if (o.deformation[i].positions.size() != n)
            throwSceneError(loc, name + " deformation key " + std::to_string(i) + " has " +
                                     std::to_string(o.deformation[i].positions.size()) + " vertices, the mesh has " +
                                     std::to_string(n));
        checkPositions(o.deformation[i].positions, loc, name + " deformation key " + std::to_string(i));
    }
}

// Bounds of the object's world positions at time t.
std::pair<glm::dvec3, glm::dvec3> worldBounds(const Object& o, double t) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity());
    glm::dvec3 hi(-std::numeric_limits<double>::infinity());
    std::vector<glm::dvec3> world;
    evalVertices(o, t, world);
    for (const glm::dvec3& p : world) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return {lo, hi};
}

}  // namespace

bool isDegenerate(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double area2 = glm::length(glm::cross(b - a, c - a));
    const double scale = std::max({glm::dot(b - a, b - a), glm::dot(c - a, c - a), glm::dot(c - b, c - b)});
    // Relative test: a sliver whose height is below ~1e-12 of its longest edge has no usable normal.
    return !(area2 > 1e-12 * scale);
}

std::uint64_t countDegenerateTriangles(const Mesh& mesh) {
    std::uint64_t count = 0;
    for (const auto& t : mesh.triangles) {
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
            isDegenerate(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]))
            ++count;
    }
    return count;
}

bool isClosedManifold(const Mesh& mesh) {
    // Closed and consistently wound means each directed edge (a -> b) occurs once and its reverse occurs
    // once: the sorted directed edges have no repeats and equal the sorted reversed edges. Sorting two flat
    // arrays, not a hash map of every edge, keeps this linear-time check cheap on meshes of millions of
    // triangles (a node allocation per edge took a minute for 4M triangles under ASan).
    std::vector<std::uint64_t> edges, reversed;
    edges.reserve(mesh.triangles.size() * 3);
    reversed.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const std::uint64_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
            edges.push_back((a << 32) | b);
            reversed.push_back((b << 32) | a);
        }
    std::sort(edges.begin(), edges.end());
    if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
    std::sort(reversed.begin(), reversed.end());
    return !mesh.triangles.empty() && edges == reversed;
}

std::vector<std::string> validateScene(const Scene& scene, const SceneLocations& locations) {
    std::vector<std::string> warnings;
    if (scene.objects.empty()) throwSceneError({}, "the scene has no objects");

    const FileLoc no_loc;
    requireIncreasing(scene.camera.keys, locations.camera_keys, no_loc, "camera");
    if (scene.camera.keys.empty()) throwSceneError({}, "the camera has no keys");
    for (std::size_t i = 0; i < scene.camera.keys.size(); ++i) {
        const CameraKey& k = scene.camera.keys[i];
        const FileLoc loc = locAt(locations.camera_keys, i, no_loc);
        if (!sane(k.position)) throwSceneError(loc, "camera key " + std::to_string(i) + " has an absurd position");
        makeCameraFrame(k.position, k.view, k.up, loc);
    }

    for (std::size_t i = 0; i < scene.objects.size(); ++i) checkObject(scene.objects[i], i, scene, locations);

    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const Object& o = scene.objects[i];
        const std::uint64_t degenerate = countDegenerateTriangles(o.mesh);
        if (degenerate > 0)
            warnings.push_back(at(o.loc) + describe(o, i) + " has " + std::to_string(degenerate) +
                               " degenerate triangle(s) of " + std::to_string(o.mesh.triangles.size()) +
                               " (kept; they cover no area)");
        if (!isClosedManifold(o.mesh)) continue;
        for (std::size_t k = 0; k < scene.camera.keys.size(); ++k) {
            const CameraKey& key = scene.camera.keys[k];
            const auto [lo, hi] = worldBounds(o, key.time);
            const glm::dvec3& p = key.position;
            if (glm::all(glm::greaterThan(p, lo)) && glm::all(glm::lessThan(p, hi))) {
                warnings.push_back(at(locAt(locations.camera_keys, k, no_loc)) + "camera key " +
                                   std::to_string(k) + " is inside the bounds of closed " + describe(o, i) +
                                   " (defined at " + o.loc.toString() + ")");
            }
        }
    }
    return warnings;
}

SceneSummary summarizeScene(const Scene& scene) {
    SceneSummary s;
    s.objects = scene.objects.size();
    for (const Object& o : scene.objects) {
        s.triangles += o.mesh.triangles.size();
        s.degenerate_triangles += countDegenerateTriangles(o.mesh);
    }
    return s;
}

}  // namespace clipblur
