#include "io/job_loader.h"

#include "io/config/config_node.h"
#include "io/config/document_reader.h"
#include "io/config/job_schema.h"
#include "io/config/overrides.h"
#include "scene/obj_loader.h"
#include "scene/primitives.h"
#include "scene/scene_validation.h"

namespace clipblur {

namespace {

using config::MeshSource;

// `faces` receives an OBJ mesh's faces as written (left empty for primitives).
Mesh buildMesh(const MeshSource& src, const std::filesystem::path& base, std::uint64_t budget, ObjFaces& faces) {
    switch (src.kind) {
        case MeshSource::Kind::Quad: return makeQuad({src.size.x, src.size.y});
        case MeshSource::Kind::Grid: return makeGrid({src.size.x, src.size.y}, src.nx, src.nz);
        case MeshSource::Kind::Box: return makeBox(src.size);
        case MeshSource::Kind::Sphere: return makeSphere(0.5 * src.size.x, src.segments);
        case MeshSource::Kind::Obj: return loadObjMesh(base / src.obj_path, src.loc, budget, &faces);
    }
    return {};
}

RenderJob build(config::ConfigNode document, const std::filesystem::path& file,
                const std::vector<std::string>& overrides, std::vector<std::filesystem::path>* read_files) {
    for (const std::string& o : overrides) config::applyOverride(document, o);
    config::JobDescription desc = config::readJobDescription(document);
    RenderJob job = std::move(desc.job);
    job.source_file = file.string();
    job.config_hash = config::configHash(document);

    const std::filesystem::path base = file.parent_path();
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < desc.meshes.size(); ++i) {
        const MeshSource& src = desc.meshes[i];
        Object& object = job.scene.objects[i];
        const std::uint64_t budget = std::min(config::kMaxTrianglesPerObject, config::kMaxTotalTriangles - total);
        ObjFaces faces;
        object.mesh = buildMesh(src, base, budget, faces);
        if (read_files && src.kind == MeshSource::Kind::Obj) read_files->push_back(base / src.obj_path);
        total += object.mesh.triangles.size();
        for (const MeshSource::Deformation& d : src.deformation) {
            ObjFaces key_faces;
            Mesh key = loadObjMesh(base / d.obj_path, d.loc, config::kMaxTrianglesPerObject, &key_faces);
            if (read_files) read_files->push_back(base / d.obj_path);
            // Same faces, not same triangles: a quad bent non-convex at one key is split along its other
            // diagonal there, yet it is the same surface; the object's triangulation holds at every key.
            const bool same_faces = src.kind == MeshSource::Kind::Obj ? key_faces == faces
                                                                       : key.triangles == object.mesh.triangles;
            if (key.positions.size() != object.mesh.positions.size() || !same_faces)
                throwSceneError(d.loc, "deformation key '" + d.obj_path + "' does not have the topology of " +
                                           "object '" + object.name + "' (" + std::to_string(key.positions.size()) +
                                           " vertices / " + std::to_string(key.triangles.size()) +
                                           " triangles against " + std::to_string(object.mesh.positions.size()) +
                                           " / " + std::to_string(object.mesh.triangles.size()) + ")");
            object.deformation.push_back(DeformationKey{d.time, std::move(key.positions)});
        }
    }
    job.warnings = validateScene(job.scene, desc.locations);
    return job;
}

}  // namespace

RenderJob loadJob(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                  std::vector<std::filesystem::path>* read_files) {
    if (read_files) read_files->push_back(file);
    return build(config::readDocument(file), file, overrides, read_files);
}

RenderJob loadJobFromText(const std::string& text, const std::filesystem::path& file_name,
                          const std::vector<std::string>& overrides) {
    return build(config::parseDocument(text, file_name.string()), file_name, overrides, nullptr);
}

}  // namespace clipblur
