#include "scene/obj_loader.h"

#include <fstream>
#include <iterator>
#include <system_error>

#include <tiny_obj_loader.h>

namespace clipblur {

Mesh parseObjMesh(const std::string& text, const std::string& name, const FileLoc& ref,
                  std::uint64_t max_triangles) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // Material files are never opened: the job file assigns materials.
    if (!reader.ParseFromString(text, "", config) || !reader.Error().empty())
        throwSceneError(ref, "cannot parse OBJ file '" + name + "': " + reader.Error());

    const auto& vertices = reader.GetAttrib().vertices;
    Mesh mesh;
    mesh.positions.reserve(vertices.size() / 3);
    for (std::size_t i = 0; i + 2 < vertices.size(); i += 3)
        mesh.positions.emplace_back(vertices[i], vertices[i + 1], vertices[i + 2]);

    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const auto& idx = shape.mesh.indices;
        std::size_t offset = 0;
        for (const unsigned int fv : shape.mesh.num_face_vertices) {
            if (fv != 3 || offset + 3 > idx.size())
                throwSceneError(ref, "OBJ file '" + name + "' has a face with " + std::to_string(fv) +
                                         " vertices after triangulation");
            std::array<std::uint32_t, 3> tri{};
            for (int k = 0; k < 3; ++k) {
                const int v = idx[offset + k].vertex_index;
                if (v < 0 || static_cast<std::size_t>(v) >= mesh.positions.size())
                    throwSceneError(ref, "OBJ file '" + name + "' refers to vertex " + std::to_string(v + 1) +
                                             " but has " + std::to_string(mesh.positions.size()));
                tri[k] = static_cast<std::uint32_t>(v);
            }
            mesh.triangles.push_back(tri);
            if (mesh.triangles.size() > max_triangles)
                throwSceneError(ref, "OBJ file '" + name + "' has more than " + std::to_string(max_triangles) +
                                         " triangles");
            offset += 3;
        }
    }
    if (mesh.triangles.empty()) throwSceneError(ref, "OBJ file '" + name + "' has no faces");
    return mesh;
}

Mesh loadObjMesh(const std::filesystem::path& file, const FileLoc& ref, std::uint64_t max_triangles) {
    const std::string name = file.string();
    std::error_code ec;
    const auto size = std::filesystem::file_size(file, ec);
    if (ec) throwSceneError(ref, "cannot read OBJ file '" + name + "': " + ec.message());
    if (size > kMaxObjFileBytes)
        throwSceneError(ref, "OBJ file '" + name + "' is larger than " + std::to_string(kMaxObjFileBytes >> 20) + " MiB");
    std::ifstream in(file, std::ios::binary);
    if (!in) throwSceneError(ref, "cannot open OBJ file '" + name + "'");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return parseObjMesh(text, name, ref, max_triangles);
}

}  // namespace clipblur
