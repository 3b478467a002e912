#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "scene/obj_loader.h"

namespace clipblur {

namespace {

std::filesystem::path writeTemp(const std::string& name, const std::string& text) {
    const auto dir = std::filesystem::path(::testing::TempDir()) / "clipblur_obj";
    std::filesystem::create_directories(dir);
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
    const auto missing = std::filesystem::path(::testing::TempDir()) / "clipblur_obj" / "missing.obj";
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
        {(v + "f 1 2 3\nf 1/1 2/2 x/3\n").c_str(), 5, 11, "'x/3' is not a vertex index"},
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

}  // namespace clipblur
