#include "cli/scene_json_command.h"

#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "io/job_loader.h"
#include "scene/object_motion.h"

namespace clipblur::cli {

namespace {

using nlohmann::json;

json vec(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

json points(const std::vector<glm::dvec3>& ps) {
    json out = json::array();
    for (const glm::dvec3& p : ps) out.push_back(vec(p));
    return out;
}

const char* textureKind(Texture::Kind kind) {
    switch (kind) {
        case Texture::Kind::Checker: return "checker";
        case Texture::Kind::Stripe: return "stripe";
        case Texture::Kind::None: break;
    }
    return "none";
}

// The curve as [time, weight] pairs, left out for a box so a box job's export is unchanged.
json shutterJson(const Shutter& shutter) {
    json out{{"open", shutter.open}, {"close", shutter.close}};
    if (shutter.curve.empty()) return out;
    json curve = json::array();
    for (const ShutterPoint& p : shutter.curve) curve.push_back(json::array({p.time, p.weight}));
    out["curve"] = std::move(curve);
    return out;
}

json objectJson(const Object& object, const std::optional<double>& at) {
    json triangles = json::array();
    for (const auto& t : object.mesh.triangles) triangles.push_back(json::array({t[0], t[1], t[2]}));
    json transform = json::array();
    for (const TransformKey& k : object.transform)
        transform.push_back({{"time", k.time},
                             {"translate", vec(k.translate)},
                             {"rotate", json::array({k.rotate.w, k.rotate.x, k.rotate.y, k.rotate.z})},
                             {"scale", vec(k.scale)}});
    json deformation = json::array();
    for (const DeformationKey& k : object.deformation)
        deformation.push_back({{"time", k.time}, {"positions", points(k.positions)}});
    json out = {{"name", object.name},
                {"material", object.material},
                {"positions", points(object.mesh.positions)},
                {"triangles", std::move(triangles)},
                {"transform", std::move(transform)},
                {"deformation", std::move(deformation)},
                {"exact_motion", object.motion != nullptr},
                {"smooth", object.mesh.smooth()},
                {"uvs", object.mesh.hasUvs()}};
    if (at) {
        std::vector<glm::dvec3> posed;
        evalVertices(object, *at, posed);
        out["posed"] = {{"time", *at}, {"positions", points(posed)}};
    }
    return out;
}

}  // namespace

nlohmann::json sceneJson(const RenderJob& job, const std::optional<double>& at) {
    const Scene& s = job.scene;
    json camera_keys = json::array();
    for (const CameraKey& k : s.camera.keys)
        camera_keys.push_back(
            {{"time", k.time}, {"position", vec(k.position)}, {"view", vec(k.view)}, {"up", vec(k.up)}});
    json lights = json::array();
    for (const Light& l : s.lights)
        lights.push_back({{"type", l.kind == Light::Kind::Point ? "point" : "directional"},
                          {"color", vec(l.color)},
                          {"intensity", l.intensity},
                          {"direction", vec(l.direction)},
                          {"position", vec(l.position)}});
    json materials = json::array();
    for (const Material& m : s.materials)
        materials.push_back({{"base_color", vec(m.base_color)},
                             {"texture",
                              {{"kind", textureKind(m.texture.kind)},
                               {"color2", vec(m.texture.color2)},
                               {"scale", m.texture.scale}}},
                             {"two_sided", m.two_sided},
                             {"unlit", m.model == ShadingModel::Unlit},
                             {"emission", vec(m.emission)},
                             {"image", m.image.file},
                             {"emission_image", m.emission_image.file}});
    json objects = json::array();
    for (const Object& o : s.objects) objects.push_back(objectJson(o, at));
    return {{"source_file", job.source_file},
            {"config_hash", job.config_hash},
            {"film", {{"width", s.film.width}, {"height", s.film.height}, {"background", vec(s.film.background)}}},
            {"camera", {{"vfov", s.camera.vfov_degrees}, {"keys", std::move(camera_keys)}}},
            {"shutter", shutterJson(job.shutter)},
            {"frames", {{"first", job.frames.first}, {"last", job.frames.last}, {"fps", job.frames.fps}}},
            {"frame", job.frames.first},
            {"ambient", vec(s.ambient)},
            {"render",
             {{"method", methodName(job.render.method)},
              {"samples", job.render.samples},
              {"seed", job.render.seed},
              {"shadows", job.render.shadows}}},
            {"lights", std::move(lights)},
            {"materials", std::move(materials)},
            {"objects", std::move(objects)}};
}

Action addSceneJsonCommand(CLI::App& app) {
    struct Options {
        std::string job;
        std::vector<std::string> overrides;
        std::optional<double> at;
    };
    auto opts = std::make_shared<Options>();
    CLI::App* sub = app.add_subcommand("scene-json", "Load a render job and print its expanded scene as JSON");
    sub->add_option("job", opts->job, "Job file (.yaml, .yml or .json)")->required();
    sub->add_option("--set", opts->overrides, "Override a setting: key.path=value (repeatable)")
        ->allow_extra_args(false);
    sub->add_option("--at", opts->at,
                    "Also give each object's world-space vertices at this time (frames), as the renderer poses them");

    return [opts]() {
        std::cout << sceneJson(loadJob(opts->job, opts->overrides), opts->at).dump() << "\n";
        return 0;
    };
}

}  // namespace clipblur::cli
