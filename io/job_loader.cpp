#include "io/job_loader.h"

#include <cmath>
#include <fstream>
#include <iterator>

#include "io/config/config_node.h"
#include "io/config/document_reader.h"
#include "io/config/job_schema.h"
#include "io/config/overrides.h"
#include "renderer/shading/image_textures.h"
#include "renderer/shading/shading.h"
#include "scene/gltf_loader.h"
#include "scene/obj_loader.h"
#include "scene/primitives.h"
#include "scene/scene_validation.h"

namespace clipblur {

namespace {

using config::MeshSource;

// The object's mesh; an OBJ file's faces as written and material come along (none for primitives).
ObjFile buildMesh(const MeshSource& src, const std::filesystem::path& base, std::uint64_t budget) {
    ObjFile out;
    switch (src.kind) {
        case MeshSource::Kind::Quad: out.mesh = makeQuad({src.size.x, src.size.y}); break;
        case MeshSource::Kind::Grid: out.mesh = makeGrid({src.size.x, src.size.y}, src.nx, src.nz); break;
        case MeshSource::Kind::Box: out.mesh = makeBox(src.size); break;
        case MeshSource::Kind::Sphere: out.mesh = makeSphere(0.5 * src.size.x, src.segments); break;
        case MeshSource::Kind::Obj: out = loadObjFile(base / src.obj_path, src.loc, budget); break;
    }
    return out;
}

// Reads every image texture now, so that a missing or unreadable one is a scene error before rendering.
// Scenes without image textures never start the texture system.
void prepareImageTextures(const Scene& scene) {
    if (!usesImageTextures(scene)) return;
    for (const Material& m : scene.materials)
        for (const ImageTexture* image : {&m.image, &m.emission_image})
            if (!image->file.empty()) ImageTextures::shared().prepare(image->file, image->loc);
}

// Appends the glTF scene's objects and materials; its camera unless the job has its own.
// Returns the external buffer files the glTF file named.
std::vector<std::filesystem::path> addSceneFile(const config::JobDescription& desc, const std::filesystem::path& base,
                                                std::uint64_t triangles, RenderJob& job) {
    const config::SceneFileSource& src = desc.scene_file;
    GltfRequest request;
    request.ref = src.loc;
    request.fps = job.frames.fps;
    request.shutter = job.shutter;
    request.frames = job.frames;
    request.camera_name = src.camera;
    request.camera_ref = src.camera_loc;
    request.max_triangles = config::kMaxTotalTriangles - triangles;
    request.max_transform_keys = config::kMaxKeys;
    request.max_deformation_keys = config::kMaxDeformationKeys;
    for (const Object& o : job.scene.objects) request.taken_names.push_back(o.name);
    GltfScene gltf = loadGltfScene(base / src.path, request);
    const int offset = static_cast<int>(job.scene.materials.size());
    job.scene.materials.insert(job.scene.materials.end(), gltf.materials.begin(), gltf.materials.end());
    for (Object& o : gltf.objects) {
        o.material += offset;
        job.scene.objects.push_back(std::move(o));
    }
    if (job.scene.objects.empty()) throwSceneError(src.loc, "the scene has no objects");
    if (!src.job_camera) {
        if (!gltf.camera)
            throwConfigError(src.loc, "the job has no 'camera' and glTF scene '" + src.path + "' has no camera");
        job.scene.camera = *gltf.camera;
        const double film = static_cast<double>(job.scene.film.width) / job.scene.film.height;
        if (gltf.camera_aspect > 0.0 && std::abs(gltf.camera_aspect - film) > 1e-3 * film)
            gltf.warnings.push_back("the glTF camera's aspectRatio " + std::to_string(gltf.camera_aspect) +
                                    " differs from the film's " + std::to_string(film) +
                                    ": its yfov is kept, so the film shows more or less width");
    }
    job.warnings.insert(job.warnings.end(), gltf.warnings.begin(), gltf.warnings.end());
    return gltf.buffer_files;
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
        ObjFile built = buildMesh(src, base, budget);
        object.mesh = std::move(built.mesh);
        const ObjFaces& faces = built.faces;
        if (built.material && !src.job_material) {
            object.material = static_cast<int>(job.scene.materials.size());
            job.scene.materials.push_back(*built.material);
        }
        if (read_files && src.kind == MeshSource::Kind::Obj) {
            read_files->push_back(base / src.obj_path);
            read_files->insert(read_files->end(), built.material_files.begin(), built.material_files.end());
            if (built.material && !built.material->image.file.empty())
                read_files->push_back(built.material->image.file);
        }
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
    if (!desc.scene_file.path.empty()) {
        const std::filesystem::path scene_path = base / desc.scene_file.path;
        const std::vector<std::filesystem::path> buffers = addSceneFile(desc, base, total, job);
        if (read_files) {
            read_files->push_back(scene_path);
            read_files->insert(read_files->end(), buffers.begin(), buffers.end());
        }
        // The glTF file's bytes are part of what the job renders: edits to it must change the hash.
        std::ifstream in(scene_path, std::ios::binary);
        job.config_hash = config::fnv1a64Hex(job.config_hash + std::string(std::istreambuf_iterator<char>(in), {}));
    }
    prepareImageTextures(job.scene);
    std::vector<std::string> warnings = validateScene(job.scene, desc.locations);
    warnings.insert(warnings.end(), job.warnings.begin(), job.warnings.end());
    job.warnings = std::move(warnings);
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
