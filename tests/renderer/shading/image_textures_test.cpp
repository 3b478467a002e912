#include "renderer/shading/image_textures.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "renderer/render.h"
#include "renderer/test_scenes.h"
#include "support/texture_files.h"

namespace clipblur {

namespace {

// IEC 61966-2-1 decoding, written here independently of the renderer's.
double decode(std::uint8_t code) {
    const double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Bytes of a w x h image whose texels all differ: channel k of texel (i, j).
std::vector<std::uint8_t> pattern(int w, int h) {
    std::vector<std::uint8_t> rgb;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            for (int k = 0; k < 3; ++k) rgb.push_back(static_cast<std::uint8_t>((37 * i + 91 * j + 59 * k + 11) % 256));
    return rgb;
}

std::filesystem::path folder() { return std::filesystem::path(::testing::TempDir()) / "clipblur_textures"; }

}  // namespace

// Point lookups at texel centres read the texel, decoded from sRGB; halfway between two centres the
// bilinear mean; a footprint over the whole image a box average in linear light. 1e-5: texels are
// stored and filtered as float.
TEST(ImageTextures, LookupsOfAGeneratedImageAtKnownUvs) {
    const int w = 4, h = 2;
    const auto file = folder() / "lookup.png";
    const std::vector<std::uint8_t> bytes = pattern(w, h);
    testing::writeRgb8Png(file, w, h, bytes);
    ImageTextures& textures = ImageTextures::shared();
    textures.prepare(file.string(), {});
    const ImageTextures::Image* image = textures.find(file.string());
    ASSERT_NE(image, nullptr);
    const auto texel = [&](int i, int j, int k) { return decode(bytes[static_cast<std::size_t>(3 * (j * w + i) + k)]); };
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const glm::dvec3 got = textures.lookup(*image, {(i + 0.5) / w, (j + 0.5) / h}, {});
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], texel(i, j, k), 1e-5) << i << " " << j << " " << k;
        }
    const glm::dvec3 between = textures.lookup(*image, {2.0 / w, 0.5 / h}, {});
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(between[k], 0.5 * (texel(1, 0, k) + texel(2, 0, k)), 1e-5);
    // The image repeats: s = 1 + (0.5 / w) is texel 0 again.
    EXPECT_NEAR(textures.lookup(*image, {1.0 + 0.5 / w, 0.5 / h}, {}).x, texel(0, 0, 0), 1e-5);
    // A footprint of the whole image reads its coarsest level, the box average of linear texels (the
    // average of codes decoded afterwards would differ by up to 0.1 on this pattern).
    TextureFootprint all;
    all.dx = {1.0, 0.0};
    all.dy = {0.0, 1.0};
    const glm::dvec3 mean = textures.lookup(*image, {0.5, 0.5}, all);
    for (int k = 0; k < 3; ++k) {
        double sum = 0.0;
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) sum += texel(i, j, k);
        EXPECT_NEAR(mean[k], sum / (w * h), 1e-5) << k;
    }
}

TEST(ImageTextures, MissingOrUnreadableFilesAreSceneErrorsNamingThem) {
    std::filesystem::create_directories(folder());
    const auto missing = folder() / "missing.png";
    const auto broken = folder() / "broken.png";
    std::ofstream(broken) << "not a PNG";
    for (const auto& file : {missing, broken}) {
        try {
            ImageTextures::shared().prepare(file.string(), FileLoc{"a.mtl", 3, 8});
            ADD_FAILURE() << file << " prepared";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::Scene);
            EXPECT_EQ(e.loc().toString(), "a.mtl:3:8");
            EXPECT_NE(e.message().find(file.string()), std::string::npos) << e.what();
        }
    }
}

// A textured quad filling a 16 x 16 film, 2 pixels per texel with the texel centres on pixel edges: the
// bilinear image is affine inside every pixel, so the exact pixel value is the image at the pixel's
// centre, which a symmetric filter centred there also gives. The clipped render (one filtered lookup per
// fragment) must then equal the converged stochastic one (point lookups) up to sampling noise: with
// V = mean (s1 - s2)^2 / 4 the variance of the two references' average, R = mean (c - s)^2 / V is 1 plus
// noise (standard error ~0.1 over 768 values), and R < 1.5 leaves no room for a texture read upside
// down, undecoded or shifted by a texel (each off by 0.05 or more per pixel against V ~ 1e-6).
TEST(ImageTextures, TexturedQuadClippedMatchesStochastic) {
    const int film = 16, texels = 8;
    const auto file = folder() / "quad.png";
    testing::writeRgb8Png(file, texels, texels, pattern(texels, texels));
    RenderJob job = test::squareFilmJob(film);
    job.scene.materials[0].image.file = file.string();
    Object quad = test::rasterQuad(0, 0, film, film, 2.0, film);
    // rasterQuad's vertices run (x0, y0), (x1, y0), (x1, y1), (x0, y1): raster x is s, raster y is t.
    const glm::dvec2 st[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const auto& t : quad.mesh.triangles)
        for (const std::uint32_t v : t) quad.mesh.corner_uvs.push_back(st[v]);
    job.scene.objects.push_back(quad);
    const auto render = [&](Method method, std::uint64_t seed) {
        RenderJob j = job;
        j.render.method = method;
        j.render.samples = 256;
        j.render.seed = seed;
        return renderFrame(j, 0);
    };
    const RenderResult clipped = render(Method::Clipped, 0);
    const RenderResult s1 = render(Method::Stochastic, 1), s2 = render(Method::Stochastic, 2);
    double noise = 0.0, error = 0.0, contrast = 0.0;
    for (const char* c : {"R", "G", "B"}) {
        const auto& a = s1.image.find(c)->values;
        const auto& b = s2.image.find(c)->values;
        const auto& x = clipped.image.find(c)->values;
        for (std::size_t i = 0; i < x.size(); ++i) {
            noise += (double(a[i]) - b[i]) * (double(a[i]) - b[i]) / 4.0;
            const double s = 0.5 * (double(a[i]) + b[i]);
            error += (x[i] - s) * (x[i] - s);
            contrast = std::max(contrast, std::abs(x[i] - double(clipped.image.find(c)->values[0])));
        }
    }
    RecordProperty("ratio", std::to_string(error / noise));
    EXPECT_GT(contrast, 0.2) << "the texture shows";
    EXPECT_LT(error / noise, 1.5) << "noise " << noise / 768 << " error " << error / 768;
}

}  // namespace clipblur
