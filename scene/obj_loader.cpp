#include "scene/obj_loader.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

#include "scene/polygon_triangulation.h"
#include "scene/scene_validation.h"

namespace clipblur {

namespace {

struct Token {
    std::string_view text;
    int column = 0;  // 1-based, in bytes
};

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Whitespace-separated tokens of one line, up to a '#' comment.
void tokenize(std::string_view line, std::vector<Token>& out) {
    out.clear();
    std::size_t i = 0;
    while (true) {
        while (i < line.size() && isBlank(line[i])) ++i;
        if (i >= line.size() || line[i] == '#') return;
        const std::size_t start = i;
        while (i < line.size() && !isBlank(line[i])) ++i;
        out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
    }
}

// 'text', built by appending: GCC 12 warns falsely (-Wrestrict) on "'" + std::string(...).
std::string quoted(std::string_view text) {
    std::string s(1, '\'');
    s.append(text);
    s += '\'';
    return s;
}

template <typename Visit>
void forEachLine(const std::string& text, Visit&& visit) {
    const std::string_view all(text);
    int number = 1;
    for (std::size_t start = 0; start < all.size(); ++number) {
        std::size_t end = all.find('\n', start);
        if (end == std::string_view::npos) end = all.size();
        visit(all.substr(start, end - start), number);
        start = end + 1;
    }
}

// Strict: the whole token, finite (from_chars alone would take "nan" and "inf"); a leading '+' is allowed.
std::optional<double> parseCoordinate(std::string_view s) {
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    double value = 0.0;
    const char* end = s.data() + s.size();
    const auto [ptr, ec] = std::from_chars(s.data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
    return value;
}

// Face corners without a texture coordinate or normal index.
constexpr std::uint32_t kNoIndex = UINT32_MAX;

// How many `v`, `vt` and `vn` statements the file has: positive indices may name later ones.
struct StatementCounts {
    std::size_t positions = 0;
    std::size_t uvs = 0;
    std::size_t normals = 0;
};

// Reads `v`, `vt`, `vn`, `f`, `mtllib` and `usemtl` statements line by line. Faces are kept as polygons
// and triangulated at the end, since a positive index may name a vertex that comes later in the file.
class ObjParser {
public:
    ObjParser(const std::string& name, const FileLoc& ref, const StatementCounts& counts, std::uint64_t max_triangles)
        : name_(name), ref_(ref), counts_(counts), max_triangles_(max_triangles) {
        mesh_.positions.reserve(counts.positions);
    }

    // With materials off, `mtllib` and `usemtl` are skipped (deformation keys share their object's).
    bool read_materials = false;

    void read(std::string_view line, int number) {
        tokenize(line, tokens_);
        line_ = number;
        if (tokens_.empty()) return;
        const std::string_view keyword = tokens_[0].text;
        if (keyword == "v") readVertex();
        if (keyword == "vt") readUv();
        if (keyword == "vn") readNormal();
        if (keyword == "f") readFace();
        if (read_materials && keyword == "mtllib") readLibraries();
        if (read_materials && keyword == "usemtl") useMaterial();
    }

    ObjFile finish() {
        if (faces_.empty()) throwSceneError(ref_, "OBJ file '" + name_ + "' has no faces");
        ObjFile out;
        out.faces.indices = indices_;
        for (const Face& f : faces_) out.faces.starts.push_back(f.start);
        mesh_.triangles.reserve(triangles_);
        const bool uvs = !uvs_.empty(), normals = !normals_.empty();
        if (uvs) mesh_.corner_uvs.reserve(3 * triangles_);
        if (normals) mesh_.corner_normals.reserve(3 * triangles_);
        for (std::size_t f = 0; f < faces_.size(); ++f) {
            const std::size_t start = faces_[f].start;
            const std::size_t end = f + 1 < faces_.size() ? faces_[f + 1].start : indices_.size();
            line_ = faces_[f].line;
            for (const TriangleIndices& t : triangulate(start, end, faces_[f].column)) {
                const TriangleIndices tri{indices_[start + t[0]], indices_[start + t[1]], indices_[start + t[2]]};
                mesh_.triangles.push_back(tri);
                const glm::dvec3 face_normal = glm::cross(mesh_.positions[tri[1]] - mesh_.positions[tri[0]],
                                                          mesh_.positions[tri[2]] - mesh_.positions[tri[0]]);
                for (int k = 0; k < 3; ++k) {
                    const std::uint32_t vt = uv_indices_[start + t[static_cast<std::size_t>(k)]];
                    const std::uint32_t vn = normal_indices_[start + t[static_cast<std::size_t>(k)]];
                    if (uvs) mesh_.corner_uvs.push_back(vt == kNoIndex ? glm::dvec2(0.0) : uvs_[vt]);
                    if (normals) mesh_.corner_normals.push_back(vn == kNoIndex ? face_normal : normals_[vn]);
                }
            }
        }
        out.mesh = std::move(mesh_);
        out.material = std::move(material_);
        out.material_files = std::move(material_files_);
        return out;
    }

private:
    struct Face {
        std::size_t start;  // into indices_
        int line;
        int column;
    };

    [[noreturn]] void fail(int column, const std::string& message) const {
        const std::string where = ref_.toString();
        throw Error(ExitCode::Scene, message + (where.empty() ? "" : " (OBJ file of " + where + ")"),
                    FileLoc{name_, line_, column});
    }

    double number(const Token& t) const {
        const auto value = parseCoordinate(t.text);
        if (!value) fail(t.column, quoted(t.text) + " is not a finite number");
        return *value;
    }

    // The statement's numbers after the keyword: at least `least` (named `what`), at most `most`.
    void checkCount(std::size_t least, std::size_t most, const std::string& what) const {
        if (tokens_.size() < least + 1)
            fail(tokens_[0].column, "'" + std::string(tokens_[0].text) + "' needs " + what + "; this one has " +
                                        std::to_string(tokens_.size() - 1) + " numbers");
        if (tokens_.size() > most + 1)
            fail(tokens_[most + 1].column, "'" + std::string(tokens_[0].text) + "' has at most " +
                                               std::to_string(most) + " numbers");
    }

    glm::dvec3 bounded(std::size_t count) const {
        glm::dvec3 p(0.0);
        for (std::size_t k = 0; k < count; ++k) {
            const Token& t = tokens_[k + 1];
            p[static_cast<int>(k)] = number(t);
            if (std::abs(p[static_cast<int>(k)]) > kMaxCoordinate)
                fail(t.column, "coordinate " + std::string(t.text) + " is beyond the limit of 1e8 in magnitude");
        }
        return p;
    }

    void readVertex() {
        if (tokens_.size() < 4)
            fail(tokens_[0].column, "a vertex needs x, y and z; this one has " + std::to_string(tokens_.size() - 1));
        // x y z, then an optional w or r g b.
        if (tokens_.size() > 7) fail(tokens_[7].column, "a vertex has at most 6 numbers (x y z, then w or r g b)");
        const glm::dvec3 p = bounded(3);
        for (std::size_t k = 4; k < tokens_.size(); ++k) number(tokens_[k]);
        mesh_.positions.push_back(p);
    }

    // u v [w]; v flipped so that t runs down the image, as the texture system (and glTF) reads it.
    void readUv() {
        checkCount(2, 3, "u and v");
        const glm::dvec3 uvw = bounded(tokens_.size() - 1);
        uvs_.push_back(glm::dvec2(uvw.x, 1.0 - uvw.y));
    }

    void readNormal() {
        checkCount(3, 3, "x, y and z");
        normals_.push_back(bounded(3));
    }

    // One index of a corner, checked against the statements of its kind the file has.
    std::uint32_t index(std::string_view text, const Token& t, const char* kind, std::size_t read,
                        std::size_t total) const {
        long long index = 0;
        const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), index);
        if (text.empty() || ec != std::errc() || ptr != text.data() + text.size())
            fail(t.column, quoted(t.text) + " is not a " + std::string(kind) + " index");
        const auto before = static_cast<long long>(read);
        const std::string plural = std::string(kind) + (std::string_view(kind) == "vertex" ? "" : "s");
        if (index == 0) fail(t.column, std::string(kind) + " index 0 does not exist (indices start at 1)");
        if (index < -before)
            fail(t.column, std::string(kind) + " index " + std::to_string(index) + " does not exist: " +
                               std::to_string(read) + (std::string_view(kind) == "vertex" ? " vertices" : " " + plural) +
                               " precede it");
        if (index > static_cast<long long>(total))
            fail(t.column, std::string(kind) + " index " + std::to_string(index) + " does not exist: the file has " +
                               std::to_string(total) + (std::string_view(kind) == "vertex" ? " vertices" : " " + plural));
        return static_cast<std::uint32_t>(index < 0 ? before + index : index - 1);
    }

    // "v", "v/vt", "v//vn" or "v/vt/vn".
    void readCorner(const Token& t) {
        const std::string_view text = t.text;
        const std::size_t slash = text.find('/');
        indices_.push_back(index(text.substr(0, slash), t, "vertex", mesh_.positions.size(), counts_.positions));
        std::uint32_t vt = kNoIndex, vn = kNoIndex;
        if (slash != std::string_view::npos) {
            const std::string_view rest = text.substr(slash + 1);
            const std::size_t second = rest.find('/');
            const std::string_view uv = rest.substr(0, second);
            if (!uv.empty()) vt = index(uv, t, "texture coordinate", uvs_.size(), counts_.uvs);
            if (second != std::string_view::npos)
                vn = index(rest.substr(second + 1), t, "normal", normals_.size(), counts_.normals);
        }
        uv_indices_.push_back(vt);
        normal_indices_.push_back(vn);
    }

    void readFace() {
        const std::size_t corners = tokens_.size() - 1;
        if (corners < 3)
            fail(tokens_[0].column, "a face needs at least 3 vertices; this one has " + std::to_string(corners));
        triangles_ += corners - 2;
        if (triangles_ > max_triangles_)
            fail(tokens_[0].column, "the file has more than " + std::to_string(max_triangles_) + " triangles");
        faces_.push_back({indices_.size(), line_, tokens_[0].column});
        for (std::size_t k = 1; k < tokens_.size(); ++k) readCorner(tokens_[k]);
    }

    // Triangles of face corners [start, end) as corner offsets from start.
    std::vector<TriangleIndices> triangulate(std::size_t start, std::size_t end, int column) const {
        PolygonFace local(end - start);
        for (std::size_t k = 0; k < local.size(); ++k) local[k] = static_cast<std::uint32_t>(k);
        std::vector<TriangleIndices> out;
        if (local.size() == 3) return {{0, 1, 2}};
        const PolygonFace face(indices_.begin() + static_cast<std::ptrdiff_t>(start),
                               indices_.begin() + static_cast<std::ptrdiff_t>(end));
        const std::vector<glm::dvec2> polygon = projectFace(mesh_.positions, face);
        if (isConvexPolygon(polygon)) {
            triangulateConvex(local, out);
            return out;
        }
        if (face.size() > kMaxConcaveFaceVertices)
            fail(column, "a non-convex face of " + std::to_string(face.size()) + " vertices; at most " +
                             std::to_string(kMaxConcaveFaceVertices) + " are allowed (split it)");
        triangulateByEarClipping(polygon, local, out);
        return out;
    }

    void readLibraries() {
        if (tokens_.size() < 2) fail(tokens_[0].column, "'mtllib' needs a file name");
        for (std::size_t k = 1; k < tokens_.size(); ++k) {
            const std::filesystem::path file = std::filesystem::path(name_).parent_path() / std::string(tokens_[k].text);
            std::error_code ec;
            if (!std::filesystem::is_regular_file(file, ec))
                fail(tokens_[k].column, "material library '" + file.string() + "' does not exist");
            readMaterialLibrary(file);
            material_files_.push_back(file);
        }
    }

    void readMaterialLibrary(const std::filesystem::path& file);

    void useMaterial() {
        if (tokens_.size() != 2) fail(tokens_[0].column, "'usemtl' needs one material name");
        const std::string wanted(tokens_[1].text);
        if (material_name_ && *material_name_ == wanted) return;
        if (material_name_)
            fail(tokens_[1].column, "a second material '" + wanted + "' after '" + *material_name_ +
                                        "': one material per OBJ file (split the file into objects)");
        const auto it = library_.find(wanted);
        if (it == library_.end()) fail(tokens_[1].column, "material '" + wanted + "' is in no material library read");
        material_name_ = wanted;
        material_ = it->second;
    }

    const std::string& name_;
    const FileLoc& ref_;
    StatementCounts counts_;
    std::uint64_t max_triangles_;
    std::uint64_t triangles_ = 0;
    std::vector<Token> tokens_;
    int line_ = 0;
    Mesh mesh_;
    std::vector<glm::dvec2> uvs_;
    std::vector<glm::dvec3> normals_;
    std::vector<std::uint32_t> indices_, uv_indices_, normal_indices_;
    std::vector<Face> faces_;
    std::map<std::string, Material> library_;
    std::optional<std::string> material_name_;
    std::optional<Material> material_;
    std::vector<std::filesystem::path> material_files_;
};

std::string readText(const std::filesystem::path& file, const FileLoc& ref, const char* what) {
    const std::string name = file.string();
    std::error_code ec;
    const auto size = std::filesystem::file_size(file, ec);
    if (ec) throwSceneError(ref, std::string("cannot read ") + what + " '" + name + "': " + ec.message());
    if (size > kMaxObjFileBytes)
        throwSceneError(ref, std::string(what) + " '" + name + "' is larger than " +
                                 std::to_string(kMaxObjFileBytes >> 20) + " MiB");
    std::ifstream in(file, std::ios::binary);
    if (!in) throwSceneError(ref, std::string("cannot open ") + what + " '" + name + "'");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// `newmtl`, `Kd` and `map_Kd` of one .mtl file; errors located in it.
void ObjParser::readMaterialLibrary(const std::filesystem::path& file) {
    const FileLoc at{name_, line_, tokens_[0].column};
    const std::string text = readText(file, at, "material library");
    const std::string mtl = file.string();
    std::vector<Token> tokens;
    Material* current = nullptr;
    forEachLine(text, [&](std::string_view line, int number) {
        tokenize(line, tokens);
        if (tokens.empty()) return;
        const auto failHere = [&](int column, const std::string& message) {
            throw Error(ExitCode::Scene, message, FileLoc{mtl, number, column});
        };
        const std::string_view keyword = tokens[0].text;
        if (keyword == "newmtl") {
            if (tokens.size() != 2) failHere(tokens[0].column, "'newmtl' needs one material name");
            current = &library_[std::string(tokens[1].text)];
            *current = Material{};
            return;
        }
        if (keyword != "Kd" && keyword != "map_Kd") return;
        if (!current) failHere(tokens[0].column, "'" + std::string(keyword) + "' before any 'newmtl'");
        if (keyword == "Kd") {
            if (tokens.size() != 4) failHere(tokens[0].column, "'Kd' needs r, g and b");
            for (int k = 0; k < 3; ++k) {
                const Token& t = tokens[static_cast<std::size_t>(k) + 1];
                const auto value = parseCoordinate(t.text);
                if (!value || *value < 0.0) failHere(t.column, quoted(t.text) + " is not a colour value (a number >= 0)");
                current->base_color[k] = *value;
            }
            return;
        }
        if (tokens.size() < 2) failHere(tokens[0].column, "'map_Kd' needs a file name");
        if (tokens[1].text.front() == '-')
            failHere(tokens[1].column, "'map_Kd' options (" + std::string(tokens[1].text) + ") are not supported");
        std::string_view rest = line.substr(static_cast<std::size_t>(tokens[1].column) - 1);
        rest = rest.substr(0, rest.find('#'));
        while (!rest.empty() && isBlank(rest.back())) rest.remove_suffix(1);
        const std::filesystem::path image = file.parent_path() / std::string(rest);
        std::error_code ec;
        if (!std::filesystem::is_regular_file(image, ec))
            failHere(tokens[1].column, "texture file '" + image.string() + "' does not exist");
        current->image.file = image.string();
        current->image.loc = FileLoc{mtl, number, tokens[1].column};
    });
}

StatementCounts countStatements(const std::string& text) {
    StatementCounts count;
    forEachLine(text, [&](std::string_view line, int) {
        std::size_t i = 0;
        while (i < line.size() && isBlank(line[i])) ++i;
        if (i + 1 >= line.size() || line[i] != 'v') return;
        if (isBlank(line[i + 1])) ++count.positions;
        if (i + 2 < line.size() && isBlank(line[i + 2])) {
            if (line[i + 1] == 't') ++count.uvs;
            if (line[i + 1] == 'n') ++count.normals;
        }
    });
    return count;
}

// Whether `mtllib` and `usemtl` are read (a file's own materials) or ignored (a mesh alone).
enum class Materials { Ignored, Read };

ObjFile parse(const std::string& text, const std::string& name, const FileLoc& ref, std::uint64_t max_triangles,
              Materials materials) {
    ObjParser parser(name, ref, countStatements(text), max_triangles);
    parser.read_materials = materials == Materials::Read;
    forEachLine(text, [&](std::string_view line, int number) { parser.read(line, number); });
    return parser.finish();
}

}  // namespace

Mesh parseObjMesh(const std::string& text, const std::string& name, const FileLoc& ref,
                  std::uint64_t max_triangles, ObjFaces* faces) {
    ObjFile file = parse(text, name, ref, max_triangles, Materials::Ignored);
    if (faces) *faces = std::move(file.faces);
    return std::move(file.mesh);
}

Mesh loadObjMesh(const std::filesystem::path& file, const FileLoc& ref, std::uint64_t max_triangles,
                 ObjFaces* faces) {
    return parseObjMesh(readText(file, ref, "OBJ file"), file.string(), ref, max_triangles, faces);
}

ObjFile parseObjFile(const std::string& text, const std::string& name, const FileLoc& ref,
                     std::uint64_t max_triangles) {
    return parse(text, name, ref, max_triangles, Materials::Read);
}

ObjFile loadObjFile(const std::filesystem::path& file, const FileLoc& ref, std::uint64_t max_triangles) {
    return parseObjFile(readText(file, ref, "OBJ file"), file.string(), ref, max_triangles);
}

}  // namespace clipblur
