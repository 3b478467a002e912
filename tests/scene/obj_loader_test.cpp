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

}  // namespace clipblur
