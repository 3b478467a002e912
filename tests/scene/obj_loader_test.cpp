#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "scene/obj_loader.h"

namespace clipblur {

namespace {

// The test's own directory: ctest runs tests side by side, and two that wrote bad0.obj in one directory
// read each other's file.
std::filesystem::path testFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const auto dir = std::filesystem::path(::testing::TempDir()) / "clipblur_obj" / info->name();
    std::filesystem::create_directories(dir);
    return dir;
}

std::filesystem::path writeTemp(const std::string& name, const std::string& text) {
    const auto dir = testFolder();
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
}

// The location and message of the error loading `text`, which must fail.
Error loadError(const std::string& name, const std::string& text) {
    try {
        loadObjMesh(writeTemp(name, text), FileLoc{"job.yaml", 7, 10}, 100000);
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << name << " loaded";
    return Error(ExitCode::Ok, "");
}

// "v x y 0" exactly: a circle's vertices must stay convex after printing.
std::string vertexLine(double x, double y) {
    char line[80];
    std::snprintf(line, sizeof line, "v %.17g %.17g 0\n", x, y);
    return line;
}

struct BadObj {
    const char* text;
    int line;
    int column;
    const char* says;
};

void expectLocatedErrors(const std::vector<BadObj>& cases) {
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const std::string name = "bad" + std::to_string(i) + ".obj";
        SCOPED_TRACE(cases[i].text);
        const Error e = loadError(name, cases[i].text);
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_EQ(e.loc().line, cases[i].line);
        EXPECT_EQ(e.loc().column, cases[i].column);
        EXPECT_NE(e.loc().file.find(name), std::string::npos) << e.what();
        EXPECT_NE(e.message().find(cases[i].says), std::string::npos) << e.what();
        EXPECT_NE(e.message().find("job.yaml:7:10"), std::string::npos) << e.what();
    }
}

}  // namespace

TEST(ObjLoader, RoundTripOfASmallFile) {
    // Two shapes, a quad polygon (fanned into two triangles), a triangle with negative (relative) indices,
    // and attributes the loader must ignore.
    const auto path = writeTemp("round.obj",
                                "# test\nmtllib none.mtl\no a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                "vt 0 0\nf 1/1/1 2/1/1 3/1/1 4/1/1\no b\nv 0 0 2\nv 1 0 2\nv 0 1 2.5\nf -3 -2 -1\n");
    const Mesh m = loadObjMesh(path, FileLoc{"job.yaml", 3, 4}, 100);
    ASSERT_EQ(m.positions.size(), 7u);
    EXPECT_EQ(m.positions[6], glm::dvec3(0, 1, 2.5));
    ASSERT_EQ(m.triangles.size(), 3u);
    // The unit quad splits into two triangles that keep its winding (+z) and cover area 1 together.
    double area = 0.0;
    for (int i = 0; i < 2; ++i) {
        const auto& t = m.triangles[i];
        for (const std::uint32_t v : t) EXPECT_LT(v, 4u);
        const glm::dvec3 n = 0.5 * glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
        EXPECT_GT(n.z, 0.0);
        area += n.z;
    }
    EXPECT_NEAR(area, 1.0, 1e-15);
    EXPECT_EQ(m.triangles[2], (std::array<std::uint32_t, 3>{4, 5, 6}));
}

TEST(ObjLoader, ErrorsCarryTheReferenceLocation) {
    const FileLoc ref{"job.yaml", 7, 10};
    const auto missing = testFolder() / "missing.obj";
    try {
        loadObjMesh(missing, ref, 100);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_EQ(e.loc().toString(), "job.yaml:7:10");
    }
    EXPECT_THROW(loadObjMesh(writeTemp("empty.obj", "v 0 0 0\n"), ref, 100), Error);
    EXPECT_THROW(loadObjMesh(writeTemp("range.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n"), ref, 100), Error);
    EXPECT_THROW(loadObjMesh(writeTemp("many.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\n"), ref, 1), Error);
}

// Issue 24, kind 1: tinyobjloader read what it could not parse as 0.
TEST(ObjLoader, CoordinatesThatAreNotFiniteNumbersAreLocated) {
    const std::string tri = "\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    expectLocatedErrors({
        {("v nan 0 0" + tri).c_str(), 1, 3, "'nan' is not a finite number"},
        {("v 0 inf 0" + tri).c_str(), 1, 5, "'inf' is not a finite number"},
        {("# c\nv 0 0 -infinity" + tri).c_str(), 2, 7, "'-infinity' is not a finite number"},
        {("v 0 0 1x" + tri).c_str(), 1, 7, "'1x' is not a finite number"},
        {("v\t0 \xff\xfe 0" + tri).c_str(), 1, 5, "is not a finite number"},
        {("v 1e400 0 0" + tri).c_str(), 1, 3, "'1e400' is not a finite number"},
        {("v 0 -2e8 0" + tri).c_str(), 1, 5, "beyond the limit of 1e8"},
        {("v 0 0" + tri).c_str(), 1, 1, "a vertex needs x, y and z; this one has 2"},
        {("v 0 0 0 1 2 3 4" + tri).c_str(), 1, 15, "at most 6 numbers"},
        {("v 0 0 0 w" + tri).c_str(), 1, 9, "'w' is not a finite number"},
    });
}

// Issue 24, kind 2: faces with a missing vertex or fewer than three were dropped without a word.
TEST(ObjLoader, FacesWithMissingOrTooFewVerticesAreLocated) {
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    expectLocatedErrors({
        {(v + "f 1 2 9\n").c_str(), 4, 7, "vertex index 9 does not exist: the file has 3 vertices"},
        {(v + "f 1 2\n").c_str(), 4, 1, "a face needs at least 3 vertices; this one has 2"},
        {(v + "  f\n").c_str(), 4, 3, "this one has 0"},
        {(v + "f 0 1 2\n").c_str(), 4, 3, "vertex index 0 does not exist"},
        {(v + "f 1 -4 2\n").c_str(), 4, 5, "vertex index -4 does not exist: 3 vertices precede it"},
        {(v + "vt 0 0\nvt 1 0\nf 1 2 3\nf 1/1 2/2 x/3\n").c_str(), 7, 11, "'x/3' is not a vertex index"},
        {(v + "f 1 2 3.5\n").c_str(), 4, 7, "'3.5' is not a vertex index"},
        {(v + "f 1 2 -9223372036854775808\n").c_str(), 4, 7, "does not exist"},
        {(v + "f 1 2 99999999999999999999\n").c_str(), 4, 7, "is not a vertex index"},
    });
}

TEST(ObjLoader, FacesMayNameVerticesDefinedLater) {
    const Mesh m = loadObjMesh(writeTemp("later.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"), {}, 100);
    ASSERT_EQ(m.triangles.size(), 1u);
    EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
}

// Polygons: n - 2 triangles covering the polygon's area, winding kept (concave ones too); a
// non-convex face too large to ear-clip in bounded time is refused at its line.
TEST(ObjLoader, PolygonsBecomeTrianglesOfTheirArea) {
    const auto area = [](const Mesh& m) {
        double sum = 0.0;
        for (const auto& t : m.triangles) {
            const glm::dvec3 n = glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
            EXPECT_GT(n.z, 0.0);
            sum += 0.5 * n.z;
        }
        return sum;
    };
    const Mesh ell = loadObjMesh(writeTemp("ell.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
                                                      "f 1 2 3 4 5 6\n"), {}, 100);
    EXPECT_EQ(ell.triangles.size(), 4u);
    EXPECT_NEAR(area(ell), 3.0, 1e-12);

    std::string big;
    const int n = static_cast<int>(kMaxConcaveFaceVertices) + 2;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * M_PI * i / n, r = i % 2 ? 0.5 : 1.0;
        big += vertexLine(r * std::cos(a), r * std::sin(a));
    }
    std::string face = "f";
    for (int i = 1; i <= n; ++i) face += " " + std::to_string(i);
    expectLocatedErrors({{(big + "\n" + face + "\n").c_str(), n + 2, 1, "a non-convex face of 1026 vertices"}});
    const Mesh circle = loadObjMesh(writeTemp("circle.obj", [&] {
        std::string text;
        for (int i = 0; i < n; ++i)
            text += vertexLine(std::cos(2.0 * M_PI * i / n), std::sin(2.0 * M_PI * i / n));
        return text + face + "\n";
    }()), {}, 2000);
    EXPECT_EQ(circle.triangles.size(), static_cast<std::size_t>(n - 2));
}

// Corner attributes: `f v/vt/vn` picks each corner's own normal and texture coordinate, a polygon's
// triangles keep their corners' attributes, vt's v is flipped to t down, and the one `usemtl` names the
// .mtl material (Kd, map_Kd relative to the .mtl file, which is in another folder than the OBJ).
TEST(ObjLoader, NormalsUvsAndMaterialOfTheFaceCorners) {
    const auto dir = testFolder();
    std::filesystem::create_directories(dir / "lib" / "maps");
    std::ofstream(dir / "lib" / "maps" / "wood.png") << "not read by the OBJ loader";
    std::ofstream(dir / "lib" / "wood.mtl") << "# a comment\nnewmtl other\nKd 1 0 0\n"
                                               "newmtl wood\nKa 1 1 1\nKd 0.5 0.25 0.125\nmap_Kd maps/wood.png\n";
    const ObjFile file = loadObjFile(writeTemp("attributes.obj",
                                               "mtllib lib/wood.mtl\n"
                                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                               "vn 0 0 1\nvn 1 0 0\nvn 0 1 0\nvn 0 0 -1\n"
                                               "usemtl wood\n"
                                               "f 1/1/4 2/2/3 3/3/2 4/4/1\n"
                                               "usemtl wood\n"
                                               "f 1//1 3//2 4//3\n"),
                                      {}, 100);
    const Mesh& m = file.mesh;
    ASSERT_EQ(m.triangles.size(), 3u);
    ASSERT_EQ(m.corner_normals.size(), 9u);
    ASSERT_EQ(m.corner_uvs.size(), 9u);
    // Every corner of the quad's two triangles carries the attributes its position was given with: the
    // quad's corner at position i (0-based) has vt i+1 and vn 4-i.
    const glm::dvec2 uv[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};  // (u, 1 - v)
    const glm::dvec3 normal[4] = {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
    for (std::size_t c = 0; c < 6; ++c) {
        const std::uint32_t p = m.triangles[c / 3][c % 3];
        EXPECT_EQ(m.corner_uvs[c], uv[p]) << "corner " << c;
        EXPECT_EQ(m.corner_normals[c], normal[p]) << "corner " << c;
    }
    // The last face has normals but no texture coordinates: (0, 0).
    EXPECT_EQ(m.corner_normals[6], glm::dvec3(0, 0, 1));
    EXPECT_EQ(m.corner_normals[8], glm::dvec3(0, 1, 0));
    EXPECT_EQ(m.corner_uvs[7], glm::dvec2(0.0));
    ASSERT_TRUE(file.material.has_value());
    EXPECT_EQ(file.material->base_color, glm::dvec3(0.5, 0.25, 0.125));
    EXPECT_EQ(std::filesystem::path(file.material->image.file), dir / "lib" / "maps" / "wood.png");
    EXPECT_EQ(file.material->image.loc.line, 7);
    // Deformation keys read the same file without its materials.
    const Mesh plain = loadObjMesh(dir / "attributes.obj", {}, 100);
    EXPECT_EQ(plain.triangles, m.triangles);
    EXPECT_EQ(plain.corner_uvs, m.corner_uvs);

    // Without vn or vt the mesh stays faceted and without UVs, as before.
    const ObjFile bare = loadObjFile(writeTemp("bare.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), {}, 100);
    EXPECT_FALSE(bare.mesh.smooth());
    EXPECT_FALSE(bare.mesh.hasUvs());
    EXPECT_FALSE(bare.material.has_value());
}

TEST(ObjLoader, BadAttributeIndicesAreLocated) {
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
    expectLocatedErrors({
        {(v + "f 1/2 2 3\n").c_str(), 6, 3, "texture coordinate index 2 does not exist: the file has 1"},
        {(v + "f 1//0 2 3\n").c_str(), 6, 3, "normal index 0 does not exist"},
        {(v + "f 1/1/-2 2 3\n").c_str(), 6, 3, "normal index -2 does not exist: 1 normals precede it"},
        {(v + "f 1/x 2 3\n").c_str(), 6, 3, "'1/x' is not a texture coordinate index"},
        {(v + "vt 1\nf 1 2 3\n").c_str(), 6, 1, "'vt' needs u and v"},
        {(v + "vn 0 nan 1\nf 1 2 3\n").c_str(), 6, 6, "'nan' is not a finite number"},
    });
}

// Materials: a missing library, a missing texture file (located in the .mtl), an unknown material and a
// second material in one file are scene errors at the line that names them.
TEST(ObjLoader, MaterialErrorsAreLocated) {
    const auto dir = testFolder();
    std::ofstream(dir / "two.mtl") << "newmtl a\nKd 1 1 1\nnewmtl b\nKd 0 0 0\n";
    std::ofstream(dir / "bad.mtl") << "newmtl a\nKd 1 1 1\nmap_Kd  nowhere.png\n";
    std::ofstream(dir / "negative.mtl") << "newmtl a\nKd 1 -1 1\n";
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const auto error = [&](const std::string& name, const std::string& text) {
        try {
            loadObjFile(writeTemp(name, text), FileLoc{"job.yaml", 7, 10}, 100);
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::Scene);
            return e;
        }
        ADD_FAILURE() << name << " loaded";
        return Error(ExitCode::Ok, "");
    };
    Error e = error("nolib.obj", "mtllib none.mtl\n" + tri);
    EXPECT_EQ(e.loc().line, 1);
    EXPECT_EQ(e.loc().column, 8);
    EXPECT_NE(e.message().find("material library"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("none.mtl"), std::string::npos) << e.what();
    e = error("notex.obj", "mtllib bad.mtl\n" + tri);
    EXPECT_NE(e.loc().file.find("bad.mtl"), std::string::npos) << e.what();
    EXPECT_EQ(e.loc().line, 3);
    EXPECT_EQ(e.loc().column, 9);
    EXPECT_NE(e.message().find("nowhere.png' does not exist"), std::string::npos) << e.what();
    e = error("negative.obj", "mtllib negative.mtl\n" + tri);
    EXPECT_EQ(e.loc().line, 2);
    EXPECT_EQ(e.loc().column, 6);
    e = error("unknown.obj", "mtllib two.mtl\nusemtl c\n" + tri);
    EXPECT_EQ(e.loc().line, 2);
    EXPECT_NE(e.message().find("material 'c' is in no material library"), std::string::npos) << e.what();
    e = error("second.obj", "mtllib two.mtl\nusemtl a\n" + tri + "usemtl b\nf 1 2 3\n");
    EXPECT_EQ(e.loc().line, 7);
    EXPECT_EQ(e.loc().column, 8);
    EXPECT_NE(e.message().find("one material per OBJ file"), std::string::npos) << e.what();
}

}  // namespace clipblur
