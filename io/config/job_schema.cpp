#include "io/config/job_schema.h"

#include <cmath>
#include <map>
#include <sstream>

#include <glm/gtc/quaternion.hpp>

#include "io/config/schema_reader.h"
#include "scene/camera.h"
#include "scene/primitives.h"
#include "scene/scene_validation.h"

namespace clipblur::config {

namespace {

constexpr double kBig = kMaxCoordinate;
constexpr double kTiny = 1e-12;

std::string indexed(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

void checkCount(const ConfigNode& list, const std::vector<ConfigNode>& items, const std::string& what, int max) {
    if (items.size() > static_cast<std::size_t>(max))
        throwConfigError(list.loc, "'" + what + "' has " + std::to_string(items.size()) + " entries, at most " +
                                       std::to_string(max) + " are allowed");
}

glm::dvec3 nonZeroDirection(MapReader& map, std::string_view key, glm::dvec3 fallback) {
    const ConfigNode* n = map.optional(key);
    if (!n) return fallback;
    const glm::dvec3 v = asVec3(*n, map.keyPath(key), -kBig, kBig, ScalarForm::Refused);
    if (!(glm::length(v) > 0.0)) throwConfigError(n->loc, "'" + map.keyPath(key) + "' must not be the zero vector");
    return v;
}

void readFilm(MapReader map, Film& film) {
    film.width = map.integer("width", film.width, 1, kMaxImageSide);
    film.height = map.integer("height", film.height, 1, kMaxImageSide);
    film.background = map.vec3("background", film.background, 0.0, kBig, ScalarForm::Allowed);
    map.finish();
}

void readCamera(MapReader map, Camera& camera, std::vector<FileLoc>& key_locs) {
    const ConfigNode* vfov = map.optional("vfov");
    const ConfigNode* focal = map.optional("focal_length");
    const ConfigNode* film_height = map.optional("film_height");
    if (vfov && (focal || film_height))
        throwConfigError(focal ? focal->loc : film_height->loc,
                         "give either 'camera.vfov' or 'camera.focal_length' with 'camera.film_height', not both");
    if (vfov) camera.vfov_degrees = asNumber(*vfov, "camera.vfov", 1e-3, 179.0);
    if (focal || film_height) {
        if (!focal || !film_height)
            throwConfigError(map.loc(), "'camera.focal_length' and 'camera.film_height' must be given together");
        const double f = asNumber(*focal, "camera.focal_length", 1e-3, 1e6);
        const double h = asNumber(*film_height, "camera.film_height", 1e-3, 1e6);
        camera.vfov_degrees = 2.0 * std::atan(0.5 * h / f) * 180.0 / M_PI;
    }
    const ConfigNode& keys_node = map.required("keys");
    const auto& keys = asList(keys_node, "camera.keys");
    if (keys.empty()) throwConfigError(keys_node.loc, "'camera.keys' needs at least one key");
    checkCount(keys_node, keys, "camera.keys", kMaxKeys);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        MapReader k(keys[i], indexed("camera.keys", i));
        CameraKey key;
        key.time = k.number("time", 0.0, -kBig, kBig);
        key.position = k.vec3("position", key.position, -kBig, kBig, ScalarForm::Refused);
        key.view = nonZeroDirection(k, "view", key.view);
        key.up = nonZeroDirection(k, "up", key.up);
        k.finish();
        // The camera basis's own test, so no key passes here that the scene check would refuse.
        try {
            makeCameraFrame(key.position, key.view, key.up, k.loc());
        } catch (const Error& e) {
            throwConfigError(e.loc(), "'" + k.path() + "': " + e.message());
        }
        camera.keys.push_back(key);
        key_locs.push_back(k.loc());
    }
    map.finish();
}

std::string shortNumber(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

// A curve point is [time, weight]; times run from open to close, strictly increasing.
std::vector<ShutterPoint> readShutterCurve(const ConfigNode& node, const Shutter& shutter) {
    const auto& items = asList(node, "shutter.curve");
    if (items.size() < 2) throwConfigError(node.loc, "'shutter.curve' needs at least two points, [open, w] .. [close, w]");
    checkCount(node, items, "shutter.curve", kMaxShutterCurvePoints);
    std::vector<ShutterPoint> curve;
    bool any_weight = false;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const std::string what = indexed("shutter.curve", i);
        const auto& pair = asList(items[i], what);
        if (pair.size() != 2) throwConfigError(items[i].loc, "'" + what + "' must be [time, weight]");
        const ShutterPoint p{asNumber(pair[0], what + ".time", -1.0, 1.0), asNumber(pair[1], what + ".weight", 0.0, kBig)};
        if (i == 0 && p.time != shutter.open)
            throwConfigError(pair[0].loc, "'" + what + "' must start the curve at 'shutter.open' (" +
                                              shortNumber(shutter.open) + ")");
        if (i + 1 == items.size() && p.time != shutter.close)
            throwConfigError(pair[0].loc, "'" + what + "' must end the curve at 'shutter.close' (" +
                                              shortNumber(shutter.close) + ")");
        if (i > 0 && !(p.time > curve.back().time))
            throwConfigError(pair[0].loc, "'" + what + "' must come after the point before it in time");
        any_weight = any_weight || p.weight > 0.0;
        curve.push_back(p);
    }
    if (!any_weight) throwConfigError(node.loc, "'shutter.curve' has no positive weight: the shutter would never open");
    return curve;
}

// Offsets from the frame; a centred shutter opens before it. The range keeps a frame's shutter within
// its neighbours' (one frame either way) and at most one frame long.
void readShutter(MapReader map, Shutter& shutter) {
    shutter.open = map.number("open", shutter.open, -1.0, 1.0);
    const ConfigNode* close = map.optional("close");
    if (close) shutter.close = asNumber(*close, "shutter.close", -1.0, 1.0);
    if (shutter.close < shutter.open)
        throwConfigError(close ? close->loc : map.loc(), "'shutter.close' must not be before 'shutter.open'");
    if (shutter.close - shutter.open > 1.0)
        throwConfigError(close ? close->loc : map.loc(), "the shutter is open longer than a frame ('shutter.close' - "
                                                         "'shutter.open' must be at most 1)");
    if (const ConfigNode* curve = map.optional("curve")) shutter.curve = readShutterCurve(*curve, shutter);
    map.finish();
}

void readFrames(MapReader map, FrameRange& frames) {
    frames.first = map.integer("first", frames.first, -kMaxFrameCount, kMaxFrameCount);
    const ConfigNode* last = map.optional("last");
    frames.last = last ? static_cast<int>(asInteger(*last, "frames.last", -kMaxFrameCount, kMaxFrameCount))
                       : frames.first;
    if (frames.last < frames.first)
        throwConfigError(last ? last->loc : map.loc(), "'frames.last' must not be before 'frames.first'");
    if (static_cast<std::int64_t>(frames.last) - frames.first >= kMaxFrameCount)
        throwConfigError(last ? last->loc : map.loc(), "more than " + std::to_string(kMaxFrameCount) + " frames");
    frames.fps = map.number("fps", frames.fps, 1e-3, 1e4);
    map.finish();
}

// A material's properties after its name; finishes the map.
Material readMaterial(MapReader& m) {
    Material mat;
    mat.base_color = m.vec3("color", mat.base_color, 0.0, kBig, ScalarForm::Allowed);
    mat.two_sided = m.boolean("two_sided", mat.two_sided);
    if (const ConfigNode* tex = m.optional("texture")) {
        MapReader t(*tex, m.keyPath("texture"));
        mat.texture.kind = asChoice(t.required("type"), t.keyPath("type"), {"checker", "stripe"}) == 0
                               ? Texture::Kind::Checker
                               : Texture::Kind::Stripe;
        mat.texture.color2 = t.vec3("color2", mat.texture.color2, 0.0, kBig, ScalarForm::Allowed);
        mat.texture.scale = t.number("scale", mat.texture.scale, kTiny, kBig);
        t.finish();
    }
    if (m.boolean("unlit", false)) mat.model = ShadingModel::Unlit;
    if (const ConfigNode* emission = m.optional("emission")) {
        // An unlit material shows its colour alone; emission there would be silently dropped.
        if (mat.model == ShadingModel::Unlit)
            throwConfigError(emission->loc, "'" + m.keyPath("emission") + "' has no effect on an unlit material");
        mat.emission = asVec3(*emission, m.keyPath("emission"), 0.0, kBig, ScalarForm::Allowed);
    }
    m.finish();
    return mat;
}

std::map<std::string, int> readMaterials(const ConfigNode* node, std::vector<Material>& materials) {
    std::map<std::string, int> by_name;
    if (node) {
        const auto& items = asList(*node, "materials");
        checkCount(*node, items, "materials", kMaxKeys);
        for (std::size_t i = 0; i < items.size(); ++i) {
            MapReader m(items[i], indexed("materials", i));
            const ConfigNode& name_node = m.required("name");
            const std::string name = asString(name_node, m.keyPath("name"));
            if (!by_name.emplace(name, static_cast<int>(i)).second)
                throwConfigError(name_node.loc, "duplicate material name '" + name + "'");
            materials.push_back(readMaterial(m));
        }
    }
    if (materials.empty()) materials.push_back(Material{});
    return by_name;
}

void readLights(const ConfigNode* node, std::vector<Light>& lights) {
    if (!node) return;
    const auto& items = asList(*node, "lights");
    checkCount(*node, items, "lights", kMaxKeys);
    for (std::size_t i = 0; i < items.size(); ++i) {
        MapReader l(items[i], indexed("lights", i));
        Light light;
        light.kind = asChoice(l.required("type"), l.keyPath("type"), {"directional", "point"}) == 0
                         ? Light::Kind::Directional
                         : Light::Kind::Point;
        light.color = l.vec3("color", light.color, 0.0, kBig, ScalarForm::Allowed);
        light.intensity = l.number("intensity", light.intensity, 0.0, kBig);
        // Only the key that fits the type is consumed; the other one is reported as unknown.
        if (light.kind == Light::Kind::Directional) {
            if (!l.has("direction")) l.required("direction");
            light.direction = nonZeroDirection(l, "direction", light.direction);
        } else {
            light.position = asVec3(l.required("position"), l.keyPath("position"), -kBig, kBig, ScalarForm::Refused);
        }
        l.finish();
        lights.push_back(light);
    }
}

MeshSource readPrimitive(MapReader p) {
    MeshSource src;
    src.loc = p.loc();
    src.kind = static_cast<MeshSource::Kind>(
        asChoice(p.required("type"), p.keyPath("type"), {"quad", "grid", "box", "sphere"}));
    switch (src.kind) {
        case MeshSource::Kind::Quad:
        case MeshSource::Kind::Grid: {
            if (const ConfigNode* s = p.optional("size")) {
                if (s->isScalar()) {
                    src.size = glm::dvec3(asNumber(*s, p.keyPath("size"), kTiny, kBig));
                } else if (s->isSequence() && s->items.size() == 2) {
                    src.size.x = asNumber(s->items[0], p.keyPath("size") + "[0]", kTiny, kBig);
                    src.size.y = asNumber(s->items[1], p.keyPath("size") + "[1]", kTiny, kBig);
                } else {
                    throwConfigError(s->loc, "'" + p.keyPath("size") + "' must be a number or a list of 2 numbers");
                }
            }
            if (src.kind == MeshSource::Kind::Grid) {
                src.nx = src.nz = 10;
                if (const ConfigNode* d = p.optional("divisions")) {
                    if (d->isSequence() && d->items.size() == 2) {
                        src.nx = static_cast<int>(asInteger(d->items[0], p.keyPath("divisions") + "[0]", 1, kMaxDivisions));
                        src.nz = static_cast<int>(asInteger(d->items[1], p.keyPath("divisions") + "[1]", 1, kMaxDivisions));
                    } else {
                        src.nx = src.nz = static_cast<int>(asInteger(*d, p.keyPath("divisions"), 1, kMaxDivisions));
                    }
                }
            }
            src.triangles = gridTriangleCount(src.nx, src.nz);
            break;
        }
        case MeshSource::Kind::Box:
            src.size = p.vec3("size", src.size, kTiny, kBig, ScalarForm::Allowed);
            src.triangles = 12;
            break;
        case MeshSource::Kind::Sphere:
            src.size = glm::dvec3(p.number("size", 1.0, kTiny, kBig));
            src.segments = p.integer("segments", src.segments, 3, kMaxDivisions);
            src.triangles = sphereTriangleCount(src.segments);
            break;
        case MeshSource::Kind::Obj: break;
    }
    p.finish();
    return src;
}

TransformKey readTransformKey(MapReader k) {
    TransformKey key;
    key.time = k.number("time", 0.0, -kBig, kBig);
    key.translate = k.vec3("translate", key.translate, -kBig, kBig, ScalarForm::Refused);
    if (const ConfigNode* r = k.optional("rotate")) {
        MapReader rot(*r, k.keyPath("rotate"));
        const glm::dvec3 axis = nonZeroDirection(rot, "axis", glm::dvec3(0.0, 1.0, 0.0));
        const double angle = rot.number("angle_deg", 0.0, -1e6, 1e6);
        rot.finish();
        key.rotate = glm::angleAxis(angle * M_PI / 180.0, glm::normalize(axis));
    }
    key.scale = k.vec3("scale", key.scale, kTiny, kBig, ScalarForm::Allowed);
    k.finish();
    return key;
}

void readObject(MapReader o, std::size_t index, const std::map<std::string, int>& materials, JobDescription& out) {
    Object object;
    object.loc = o.loc();
    object.name = o.string("name", "object" + std::to_string(index));
    if (const ConfigNode* m = o.optional("material")) {
        const std::string name = asString(*m, o.keyPath("material"));
        const auto it = materials.find(name);
        if (it == materials.end()) throwConfigError(m->loc, "unknown material '" + name + "'");
        object.material = it->second;
    }

    const ConfigNode* prim = o.optional("primitive");
    const ConfigNode* obj = o.optional("obj");
    if (prim && obj) throwConfigError(obj->loc, "'" + o.path() + "' has both 'primitive' and 'obj'; give one");
    if (!prim && !obj) throwConfigError(o.loc(), "'" + o.path() + "' needs a 'primitive' or an 'obj'");
    MeshSource src;
    if (prim) {
        src = readPrimitive(MapReader(*prim, o.keyPath("primitive")));
    } else {
        src.kind = MeshSource::Kind::Obj;
        src.obj_path = asString(*obj, o.keyPath("obj"));
        src.loc = obj->loc;
    }
    src.job_material = o.has("material");
    if (src.triangles > kMaxTrianglesPerObject)
        throwConfigError(src.loc, "'" + o.path() + "' would have " + std::to_string(src.triangles) +
                                      " triangles, more than the limit of " + std::to_string(kMaxTrianglesPerObject));

    std::vector<FileLoc> transform_locs;
    if (const ConfigNode* t = o.optional("transform")) {
        const auto& keys = asList(*t, o.keyPath("transform"));
        checkCount(*t, keys, o.keyPath("transform"), kMaxKeys);
        for (std::size_t i = 0; i < keys.size(); ++i) {
            object.transform.push_back(readTransformKey(MapReader(keys[i], indexed(o.keyPath("transform"), i))));
            transform_locs.push_back(keys[i].loc);
        }
    }
    std::vector<FileLoc> deformation_locs;
    if (const ConfigNode* d = o.optional("deformation")) {
        const auto& keys = asList(*d, o.keyPath("deformation"));
        checkCount(*d, keys, o.keyPath("deformation"), kMaxDeformationKeys);
        for (std::size_t i = 0; i < keys.size(); ++i) {
            MapReader k(keys[i], indexed(o.keyPath("deformation"), i));
            MeshSource::Deformation def;
            def.time = k.number("time", 0.0, -kBig, kBig);
            const ConfigNode& path = k.required("obj");
            def.obj_path = asString(path, k.keyPath("obj"));
            def.loc = path.loc;
            k.finish();
            src.deformation.push_back(def);
            deformation_locs.push_back(keys[i].loc);
        }
    }
    o.finish();
    out.job.scene.objects.push_back(std::move(object));
    out.meshes.push_back(std::move(src));
    out.locations.transform_keys.push_back(std::move(transform_locs));
    out.locations.deformation_keys.push_back(std::move(deformation_locs));
}

// `auto` (0) or a count in [1, max]; `fallback` when the key is absent.
int autoOrCount(const ConfigNode* node, const char* key, int fallback, int max) {
    if (!node) return fallback;
    if (node->isScalar() && node->scalar == "auto") return 0;
    return static_cast<int>(asInteger(*node, key, 1, max));
}

void readRender(MapReader map, RenderSettings& r, SceneFileSource& scene_file) {
    if (const ConfigNode* c = map.optional("camera")) {
        scene_file.camera = asString(*c, "render.camera");
        scene_file.camera_loc = c->loc;
        if (scene_file.camera.empty()) throwConfigError(c->loc, "'render.camera' must not be empty");
    }
    if (const ConfigNode* m = map.optional("method"))
        r.method = static_cast<Method>(
            asChoice(*m, "render.method", {"clipped", "stochastic", "accumulation", "frame0_only"}));
    r.samples = map.integer("samples", r.samples, 1, kMaxSamples);
    r.max_subframes = map.integer("max_subframes", r.max_subframes, 1, kMaxSubframes);
    r.subframes = autoOrCount(map.optional("subframes"), "render.subframes", r.subframes, r.max_subframes);
    r.max_segments = map.integer("max_segments", r.max_segments, 1, kMaxSegments);
    r.segments = autoOrCount(map.optional("segments"), "render.segments", r.segments, r.max_segments);
    if (const ConfigNode* p = map.optional("path_method"))
        r.path_method = static_cast<PathMethod>(asChoice(*p, "render.path_method", {"exact", "euler", "rk4"}));
    r.ode_steps = map.integer("ode_steps", r.ode_steps, 1, kMaxOdeSteps);
    if (const ConfigNode* t = map.optional("time_integration"))
        r.time_integration =
            static_cast<TimeIntegration>(asChoice(*t, "render.time_integration", {"subframes", "sweep", "auto"}));
    const bool spacing_given = map.has("sweep_spacing");
    r.sweep_spacing = map.number("sweep_spacing", r.sweep_spacing, 0.01, 1000.0);
    const bool reclips_given = map.has("reclip_spacing");
    r.reclip_spacing = map.number("reclip_spacing", r.reclip_spacing, 0.01, 1000.0);
    if (const ConfigNode* t = map.optional("sweep_time"))
        r.sweep_time = static_cast<SweepTime>(asChoice(*t, "render.sweep_time", {"points", "exact"}));
    if (const ConfigNode* e = map.optional("error_target")) {
        r.error_target = asNumber(*e, "render.error_target", 1e-5, 0.5);
        if (r.method != Method::Clipped)
            throwConfigError(e->loc, std::string("'render.error_target' is for render.method clipped, not ") +
                                         methodName(r.method));
        // The target picks what it needs: the spacing with sweep and auto, the subframe count with point
        // subframes; under auto a fixed subframe count would mean point subframes at that count.
        const bool spacing = r.time_integration != TimeIntegration::Subframes;
        const bool count = r.time_integration != TimeIntegration::Sweep;
        if (spacing && spacing_given)
            throwConfigError(e->loc, "'render.error_target' picks sweep_spacing: leave 'render.sweep_spacing' out");
        if (spacing && reclips_given)
            throwConfigError(e->loc, "'render.error_target' picks reclip_spacing: leave 'render.reclip_spacing' out");
        if (count && r.subframes > 0)
            throwConfigError(e->loc, "'render.error_target' picks the subframe count: leave 'render.subframes' at auto");
    }
    if (const ConfigNode* f = map.optional("fragment_shading"))
        r.fragment_shading =
            static_cast<FragmentShading>(asChoice(*f, "render.fragment_shading", {"centroid", "fan", "integral"}));
    r.visibility_rays = map.integer("visibility_rays", r.visibility_rays, 0, kMaxVisibilityRays);
    r.shadows = map.boolean("shadows", r.shadows);
    if (const ConfigNode* s = map.optional("seed")) r.seed = asUnsigned(*s, "render.seed");
    r.tile_size = map.integer("tile_size", r.tile_size, 1, kMaxTileSize);
    r.audit = map.boolean("audit", r.audit);
    map.finish();
}

// Channel names are <name>00.R ...: a '.' would start another layer, so names are [A-Za-z0-9_].
void readCryptomatte(MapReader map, CryptomatteSettings& crypto) {
    crypto.enabled = true;
    if (const ConfigNode* n = map.optional("name")) {
        crypto.name = asString(*n, map.keyPath("name"));
        const bool plain = !crypto.name.empty() && crypto.name.size() <= 64 &&
                           crypto.name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_") ==
                               std::string::npos;
        if (!plain) throwConfigError(n->loc, "'" + map.keyPath("name") + "' must be 1 to 64 of A-Z, a-z, 0-9, _");
    }
    crypto.depth = map.integer("depth", crypto.depth, 1, 32);
    map.finish();
}

void readOutput(MapReader map, OutputSettings& out) {
    if (const ConfigNode* p = map.optional("path")) {
        out.path = asString(*p, "output.path");
        if (out.path.empty()) throwConfigError(p->loc, "'output.path' must not be empty");
    }
    out.half = map.boolean("half", out.half);
    out.png_preview = map.boolean("png_preview", out.png_preview);
    const ConfigNode* compression = map.optional("compression");
    if (compression)
        out.compression =
            static_cast<ExrCompression>(asChoice(*compression, "output.compression", {"zip", "piz", "dwaa", "none"}));
    if (const ConfigNode* c = map.optional("cryptomatte")) readCryptomatte(MapReader(*c, "output.cryptomatte"), out.cryptomatte);
    // DWA compresses channels named R, G, B lossily, which would change the IDs in <name>00.R ...
    if (out.cryptomatte.enabled && out.compression == ExrCompression::Dwaa)
        throwConfigError(compression->loc, "'output.compression: dwaa' is lossy and would corrupt Cryptomatte IDs");
    if (const ConfigNode* b = map.optional("background"))
        out.background = static_cast<BackgroundMode>(asChoice(*b, "output.background", {"separate", "bake"}));
    if (const ConfigNode* a = map.optional("aovs")) {
        const auto& items = asList(*a, "output.aovs");
        for (std::size_t i = 0; i < items.size(); ++i) {
            const int which = asChoice(items[i], indexed("output.aovs", i), {"depth", "coverage", "motion"});
            bool& flag = which == 0 ? out.aov_depth : which == 1 ? out.aov_coverage : out.aov_motion;
            if (flag) throwConfigError(items[i].loc, "AOV '" + items[i].scalar + "' is listed twice");
            flag = true;
        }
    }
    out.stats_path = map.string("stats", out.stats_path);
    map.finish();
}

}  // namespace

JobDescription readJobDescription(const ConfigNode& root) {
    JobDescription out;
    RenderJob& job = out.job;
    MapReader top(root, "");
    const ConfigNode& version = top.required("version");
    if (!version.isScalar() || version.style != ConfigNode::Style::Plain || version.scalar != "1")
        throwConfigError(version.loc, "unsupported 'version' (this build reads version 1)");
    job.version = 1;

    if (const ConfigNode* n = top.optional("film")) readFilm(MapReader(*n, "film"), job.scene.film);
    SceneFileSource& scene_file = out.scene_file;
    if (const ConfigNode* n = top.optional("scene")) {
        scene_file.path = asString(*n, "scene");
        scene_file.loc = n->loc;
        if (scene_file.path.empty()) throwConfigError(n->loc, "'scene' must not be empty");
    }
    // A glTF scene may bring the camera; a `camera` block of the job then replaces it.
    const ConfigNode* camera = scene_file.path.empty() ? &top.required("camera") : top.optional("camera");
    if (camera) readCamera(MapReader(*camera, "camera"), job.scene.camera, out.locations.camera_keys);
    scene_file.job_camera = camera != nullptr;
    if (const ConfigNode* n = top.optional("shutter")) readShutter(MapReader(*n, "shutter"), job.shutter);
    if (const ConfigNode* n = top.optional("frames")) readFrames(MapReader(*n, "frames"), job.frames);
    const auto materials = readMaterials(top.optional("materials"), job.scene.materials);
    readLights(top.optional("lights"), job.scene.lights);
    job.scene.ambient = top.vec3("ambient", job.scene.ambient, 0.0, kBig, ScalarForm::Allowed);

    // With a glTF scene the job's objects are additions and may be left out.
    const ConfigNode* objects_node = scene_file.path.empty() ? &top.required("objects") : top.optional("objects");
    static const std::vector<ConfigNode> none;
    const auto& objects = objects_node ? asList(*objects_node, "objects") : none;
    if (objects_node && objects.empty()) throwSceneError(objects_node->loc, "the scene has no objects");
    if (objects_node) checkCount(*objects_node, objects, "objects", 1 << 20);
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < objects.size(); ++i) {
        readObject(MapReader(objects[i], indexed("objects", i)), i, materials, out);
        total += out.meshes.back().triangles;
        if (total > kMaxTotalTriangles)
            throwConfigError(objects[i].loc, "the scene would have more than " + std::to_string(kMaxTotalTriangles) +
                                                 " triangles");
    }
    if (const ConfigNode* n = top.optional("render")) readRender(MapReader(*n, "render"), job.render, scene_file);
    if (!scene_file.camera.empty() && scene_file.path.empty())
        throwConfigError(scene_file.camera_loc, "'render.camera' picks a camera of a glTF scene; the job has no 'scene'");
    if (!scene_file.camera.empty() && scene_file.job_camera)
        throwConfigError(scene_file.camera_loc,
                         "'render.camera' picks a glTF camera but the job has its own 'camera'; give one of them");
    if (const ConfigNode* n = top.optional("output")) readOutput(MapReader(*n, "output"), job.output);
    top.finish();
    return out;
}

}  // namespace clipblur::config
