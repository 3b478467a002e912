#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "io/job_loader.h"
#include "renderer/render.h"
#include "renderer/test_scenes.h"
#include "support/render_compare.h"

namespace clipblur {

namespace {

bool oddCell(double x, double scale) { return (static_cast<long long>(std::floor(x / scale)) & 1) != 0; }

}  // namespace

// A fronto-parallel checkered quad, rendered still with the clipped method, against its exact
// per-pixel cell coverage. On the plane z = depth facing the camera of squareFilmJob, object x and y are
// affine in raster x and y (worldAtRaster), so the cell boundaries are raster lines; each pixel is cut
// into rectangles by them and every rectangle has one albedo. shadeFragment must cut fragments along
// the same lines (it cuts along the affine zero sets of (X - k s)/z) and shade each piece by its cell.
TEST(FragmentShading, CheckerCellsAreCutExactly) {
    RenderJob job = test::squareFilmJob();
    job.render.method = Method::Clipped;
    Material checker;
    checker.base_color = glm::dvec3(1.0);
    checker.texture.kind = Texture::Kind::Checker;
    checker.texture.color2 = glm::dvec3(0.25);
    checker.texture.scale = 0.37;  // cells about 1.6 px wide at depth 6: several per pixel on some rows
    job.scene.materials.push_back(checker);
    const double depth = 6.0, x0 = 2.3, y0 = 3.1, x1 = 29.6, y1 = 27.8;
    Object quad = test::rasterQuad(x0, y0, x1, y1, depth);
    quad.material = 1;
    job.scene.objects.push_back(quad);
    const RenderResult r = renderFrame(job, 0);
    const std::vector<float>& red = r.image.find("R")->values;

    const double s = checker.texture.scale;
    // Raster x of object X: X = -(x - 16) / 16 * depth; raster y of Y: Y = (16 - y) / 16 * depth.
    std::vector<double> xs, ys;
    for (long long m = -40; m <= 40; ++m) {
        xs.push_back(16.0 - m * s * 16.0 / depth);
        ys.push_back(16.0 - m * s * 16.0 / depth);
    }
    double worst = 0.0;
    for (int py = 0; py < 32; ++py) {
        for (int px = 0; px < 32; ++px) {
            std::vector<double> bx{std::max<double>(px, x0), std::min<double>(px + 1, x1)};
            std::vector<double> by{std::max<double>(py, y0), std::min<double>(py + 1, y1)};
            if (!(bx[1] > bx[0] && by[1] > by[0])) {
                EXPECT_EQ(red[py * 32 + px], 0.0f) << px << "," << py;
                continue;
            }
            for (double x : xs)
                if (x > bx[0] && x < bx[1]) bx.push_back(x);
            for (double y : ys)
                if (y > by[0] && y < by[1]) by.push_back(y);
            std::sort(bx.begin(), bx.end());
            std::sort(by.begin(), by.end());
            double expected = 0.0;
            for (std::size_t i = 0; i + 1 < bx.size(); ++i) {
                for (std::size_t j = 0; j + 1 < by.size(); ++j) {
                    const double cx = 0.5 * (bx[i] + bx[i + 1]), cy = 0.5 * (by[j] + by[j + 1]);
                    const double X = -(cx - 16.0) / 16.0 * depth, Y = (16.0 - cy) / 16.0 * depth;
                    const bool odd = oddCell(X, s) ^ oddCell(Y, s) ^ oddCell(depth, s);
                    expected += (bx[i + 1] - bx[i]) * (by[j + 1] - by[j]) * (odd ? 0.25 : 1.0);
                }
            }
            worst = std::max(worst, std::abs(red[py * 32 + px] - expected));
        }
    }
    // Stored as float: 1e-6 is float rounding of values <= 1 with margin; a piece given the wrong cell
    // would be off by 0.75 x its area.
    EXPECT_LT(worst, 1e-6);
}

// The still textured globe (configs/shading/globe.yaml, a 256 x 128 checker image on a smooth sphere) at
// 96 x 54, about two texels per pixel: each rule's clipped render against the mean of two 512-spp
// stochastic renders (independent seeds), whose converged image is the pixel integral of the same
// bilinear image. Measured RMS: centroid 0.0115, fan 0.0045, integral 0.00036 (much of it the reference's
// own noise); the integral rule must be at least 10 times closer than centroid and 4 times than fan.
// It must also give the same bits with one thread and two.
TEST(FragmentShading, IntegralRuleIsClosestToTheStochasticGlobe) {
    const auto job = [](const std::string& rule, const std::string& method, const std::string& seed) {
        return loadJob(std::string(CLIPBLUR_SOURCE_DIR) + "/configs/shading/globe.yaml",
                       {"objects.0.transform=[]", "film.width=96", "film.height=54", "render.method=" + method,
                        "render.fragment_shading=" + rule, "render.samples=512", "render.seed=" + seed});
    };
    const RenderResult a = renderFrame(job("centroid", "stochastic", "1"), 0);
    const RenderResult b = renderFrame(job("centroid", "stochastic", "2"), 0);
    std::map<std::string, double> rmse;
    std::vector<RenderResult> integral;
    for (const char* rule : {"centroid", "fan", "integral"}) {
        const RenderResult r = renderFrame(job(rule, "clipped", "1"), 0);
        rmse[rule] = std::sqrt(testing::meanSquaredDifference(r, a, &b));
        RecordProperty(std::string("rmse_") + rule, std::to_string(rmse[rule]));
        if (std::string(rule) == "integral") integral.push_back(r);
    }
    EXPECT_LT(10.0 * rmse["integral"], rmse["centroid"]);
    EXPECT_LT(4.0 * rmse["integral"], rmse["fan"]);
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        integral.push_back(renderFrame(job("integral", "clipped", "1"), 0));
    }
    for (std::size_t c = 0; c < integral[0].image.channels.size(); ++c)
        EXPECT_EQ(integral[0].image.channels[c].values, integral[1].image.channels[c].values) << c;
}

}  // namespace clipblur
