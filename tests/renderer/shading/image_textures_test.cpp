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
    // The module's texels, which the integral rule integrates, are these decoded texels, row 0 the top.
    const ImageTextures::Texels texels = textures.texels(*image);
    ASSERT_EQ(texels.width, w);
    ASSERT_EQ(texels.height, h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(texels.rgb[static_cast<std::size_t>(3 * (j * w + i) + k)], texel(i, j, k), 1e-6);
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

// A quad filling a 32 x 32 film textured with an 8 x 8 float image whose texels are affine in (i, j):
// its bilinear image is then affine in raster space except within a texel of the wrap (texel centres at
// raster 2 and 30), so over pixels 10..21 any filter symmetric about a pixel's centre, up to 2 texels
// wide, gives the exact pixel average, and so does the integral rule. The clipped render (centroid: one
// filtered lookup per fragment; integral: the exact mean over each piece) must match
// the stochastic one (point lookups, 256 per pixel) there to 1e-4: float texels and float (s, t) round
// at 1e-7, the jittered mean of an affine function is exact to its float sum, and a lookup shifted by
// 0.01 texel or read upside down misses by 6e-4 or more (the image changes by 0.06 per texel in t).
TEST(ImageTextures, TexturedQuadClippedMatchesStochastic) {
    const int film = 32, texels = 8;
    const auto file = folder() / "ramp.exr";
    std::vector<float> ramp;
    for (int j = 0; j < texels; ++j)
        for (int i = 0; i < texels; ++i)
            for (int k = 0; k < 3; ++k) ramp.push_back(0.1f + 0.03f * static_cast<float>(i * (k + 1)) + 0.06f * static_cast<float>(j));
    testing::writeRgbFloatExr(file, texels, texels, ramp);
    RenderJob job = test::squareFilmJob(film);
    job.scene.materials[0].image.file = file.string();
    Object quad = test::rasterQuad(0, 0, film, film, 2.0, film);
    // rasterQuad's vertices run (x0, y0), (x1, y0), (x1, y1), (x0, y1): raster x is s, raster y is t.
    const glm::dvec2 st[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const auto& t : quad.mesh.triangles)
        for (const std::uint32_t v : t) quad.mesh.corner_uvs.push_back(st[v]);
    job.scene.objects.push_back(quad);
    const auto render = [&](Method method, FragmentShading rule) {
        RenderJob j = job;
        j.render.method = method;
        j.render.samples = 256;
        j.render.fragment_shading = rule;
        return renderFrame(j, 0);
    };
    const RenderResult stochastic = render(Method::Stochastic, FragmentShading::Centroid);
    for (const FragmentShading rule : {FragmentShading::Centroid, FragmentShading::Integral}) {
        const RenderResult clipped = render(Method::Clipped, rule);
        double worst = 0.0;
        for (const char* c : {"R", "G", "B"}) {
            const auto& x = clipped.image.find(c)->values;
            const auto& s = stochastic.image.find(c)->values;
            for (int py = 10; py < 22; ++py)
                for (int px = 10; px < 22; ++px) {
                    const std::size_t i = static_cast<std::size_t>(py * film + px);
                    worst = std::max(worst, std::abs(double(x[i]) - s[i]));
                }
        }
        RecordProperty("worst", std::to_string(worst));
        EXPECT_LT(worst, 1e-4);
        // The image at pixel (10, 10)'s centre, from the texels: s = t = 10.5 / 32, texel coordinate 2.125.
        const double texel = 10.5 / film * texels - 0.5;
        EXPECT_NEAR(clipped.image.find("R")->values[10 * film + 10], 0.1 + 0.03 * texel + 0.06 * texel, 1e-5);
    }
}

}  // namespace clipblur
