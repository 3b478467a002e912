#include "scene/obj_loader.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
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

// Reads `v` and `f` statements line by line. Faces are kept as polygons and triangulated at the end,
// since a positive index may name a vertex that comes later in the file.
class ObjParser {
public:
    ObjParser(const std::string& name, const FileLoc& ref, std::size_t vertex_count, std::uint64_t max_triangles)
        : name_(name), ref_(ref), vertex_count_(vertex_count), max_triangles_(max_triangles) {
        mesh_.positions.reserve(vertex_count);
    }

    void read(std::string_view line, int number) {
        tokenize(line, tokens_);
        line_ = number;
        if (tokens_.empty()) return;
        if (tokens_[0].text == "v") readVertex();
        if (tokens_[0].text == "f") readFace();
    }

    Mesh finish(ObjFaces* faces) {
        if (faces_.empty()) throwSceneError(ref_, "OBJ file '" + name_ + "' has no faces");
        if (faces) {
            faces->indices = indices_;
            faces->starts.clear();
            for (const Face& f : faces_) faces->starts.push_back(f.start);
        }
        mesh_.triangles.reserve(triangles_);
        for (std::size_t f = 0; f < faces_.size(); ++f) {
            const std::size_t end = f + 1 < faces_.size() ? faces_[f + 1].start : indices_.size();
            const PolygonFace face(indices_.begin() + static_cast<std::ptrdiff_t>(faces_[f].start),
                                   indices_.begin() + static_cast<std::ptrdiff_t>(end));
            line_ = faces_[f].line;
            triangulate(face, faces_[f].column);
        }
        return std::move(mesh_);
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

    void readVertex() {
        if (tokens_.size() < 4)
            fail(tokens_[0].column, "a vertex needs x, y and z; this one has " + std::to_string(tokens_.size() - 1));
        // x y z, then an optional w or r g b.
        if (tokens_.size() > 7) fail(tokens_[7].column, "a vertex has at most 6 numbers (x y z, then w or r g b)");
        glm::dvec3 p;
        for (int k = 0; k < 3; ++k) {
            const Token& t = tokens_[static_cast<std::size_t>(k) + 1];
            p[k] = number(t);
            if (std::abs(p[k]) > kMaxCoordinate)
                fail(t.column, "coordinate " + std::string(t.text) + " is beyond the limit of 1e8 in magnitude");
        }
        for (std::size_t k = 4; k < tokens_.size(); ++k) number(tokens_[k]);
        mesh_.positions.push_back(p);
    }

    // "v", "v/vt", "v//vn" or "v/vt/vn"; only v is used, checked against the vertices the file has.
    std::uint32_t vertexIndex(const Token& t) const {
        const std::string_view v = t.text.substr(0, t.text.find('/'));
        long long index = 0;
        const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), index);
        if (v.empty() || ec != std::errc() || ptr != v.data() + v.size())
            fail(t.column, quoted(t.text) + " is not a vertex index");
        const auto read = static_cast<long long>(mesh_.positions.size());
        if (index == 0) fail(t.column, "vertex index 0 does not exist (indices start at 1)");
        if (index < -read)
            fail(t.column, "vertex index " + std::to_string(index) + " does not exist: " + std::to_string(read) +
                               " vertices precede it");
        if (index > static_cast<long long>(vertex_count_))
            fail(t.column, "vertex index " + std::to_string(index) + " does not exist: the file has " +
                               std::to_string(vertex_count_) + " vertices");
        return static_cast<std::uint32_t>(index < 0 ? read + index : index - 1);
    }

    void readFace() {
        const std::size_t corners = tokens_.size() - 1;
        if (corners < 3)
            fail(tokens_[0].column, "a face needs at least 3 vertices; this one has " + std::to_string(corners));
        triangles_ += corners - 2;
        if (triangles_ > max_triangles_)
            fail(tokens_[0].column, "the file has more than " + std::to_string(max_triangles_) + " triangles");
        faces_.push_back({indices_.size(), line_, tokens_[0].column});
        for (std::size_t k = 1; k < tokens_.size(); ++k) indices_.push_back(vertexIndex(tokens_[k]));
    }

    void triangulate(const PolygonFace& face, int column) {
        if (face.size() == 3) {
            mesh_.triangles.push_back({face[0], face[1], face[2]});
            return;
        }
        const std::vector<glm::dvec2> polygon = projectFace(mesh_.positions, face);
        if (isConvexPolygon(polygon)) return triangulateConvex(face, mesh_.triangles);
        if (face.size() > kMaxConcaveFaceVertices)
            fail(column, "a non-convex face of " + std::to_string(face.size()) + " vertices; at most " +
                             std::to_string(kMaxConcaveFaceVertices) + " are allowed (split it)");
        triangulateByEarClipping(polygon, face, mesh_.triangles);
    }

    const std::string& name_;
    const FileLoc& ref_;
    std::size_t vertex_count_;
    std::uint64_t max_triangles_;
    std::uint64_t triangles_ = 0;
    std::vector<Token> tokens_;
    int line_ = 0;
    Mesh mesh_;
    std::vector<std::uint32_t> indices_;
    std::vector<Face> faces_;
};

std::size_t countVertices(const std::string& text) {
    std::size_t count = 0;
    forEachLine(text, [&](std::string_view line, int) {
        std::size_t i = 0;
        while (i < line.size() && isBlank(line[i])) ++i;
        if (i + 1 < line.size() && line[i] == 'v' && isBlank(line[i + 1])) ++count;
    });
    return count;
}

}  // namespace

Mesh parseObjMesh(const std::string& text, const std::string& name, const FileLoc& ref,
                  std::uint64_t max_triangles, ObjFaces* faces) {
    ObjParser parser(name, ref, countVertices(text), max_triangles);
    forEachLine(text, [&](std::string_view line, int number) { parser.read(line, number); });
    return parser.finish(faces);
}

Mesh loadObjMesh(const std::filesystem::path& file, const FileLoc& ref, std::uint64_t max_triangles,
                 ObjFaces* faces) {
    const std::string name = file.string();
    std::error_code ec;
    const auto size = std::filesystem::file_size(file, ec);
    if (ec) throwSceneError(ref, "cannot read OBJ file '" + name + "': " + ec.message());
    if (size > kMaxObjFileBytes)
        throwSceneError(ref, "OBJ file '" + name + "' is larger than " + std::to_string(kMaxObjFileBytes >> 20) + " MiB");
    std::ifstream in(file, std::ios::binary);
    if (!in) throwSceneError(ref, "cannot open OBJ file '" + name + "'");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return parseObjMesh(text, name, ref, max_triangles, faces);
}

}  // namespace clipblur
