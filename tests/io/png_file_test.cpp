#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "io/png_file.h"
#include "tests/support/cli_harness.h"

namespace clipblur {
namespace {

ImageFile rgbFile(int width, int height) {
    ImageFile f;
    f.full_width = width;
    f.full_height = height;
    f.window = PixelBounds::sized(0, 0, width, height);
    f.channels = {"R", "G", "B"};
    f.types.assign(3, PixelType::UInt8);
    for (int i = 0; i < width * height * 3; ++i) f.pixels.push_back(static_cast<float>(i * 37 % 256) / 255.0f);
    return f;
}

// OpenImageIO reads back every 8-bit code as written, and the file holds an sRGB chunk.
TEST(PngFile, WritesEightBitSrgbCodesExactly) {
    const auto dir = testing::freshTempDir("clipblur_png_file");
    const std::string path = (dir / "preview.png").string();
    const ImageFile f = rgbFile(7, 5);
    ASSERT_EQ(writePngFile(path, f), "");
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, 7);
    EXPECT_EQ(spec.height, 5);
    EXPECT_EQ(spec.nchannels, 3);
    EXPECT_EQ(spec.format, OIIO::TypeDesc::UINT8);
    std::ifstream file(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    EXPECT_NE(bytes.find("sRGB"), std::string::npos);  // the chunk; OpenImageIO would say sRGB without it
    std::vector<unsigned char> codes(7 * 5 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, codes.data()));
    for (std::size_t i = 0; i < codes.size(); ++i) EXPECT_EQ(codes[i], static_cast<int>(i * 37 % 256)) << i;
}

TEST(PngFile, RefusesWhatAnEightBitPngCannotHold) {
    const auto dir = testing::freshTempDir("clipblur_png_file_bad");
    ImageFile half = rgbFile(2, 2);
    half.types[1] = PixelType::Half;
    EXPECT_NE(writePngFile((dir / "half.png").string(), half), "");
    ImageFile windowed = rgbFile(2, 2);
    windowed.full_width = 3;
    EXPECT_NE(writePngFile((dir / "windowed.png").string(), windowed), "");
    ImageFile short_of_pixels = rgbFile(2, 2);
    short_of_pixels.pixels.pop_back();
    EXPECT_NE(writePngFile((dir / "short.png").string(), short_of_pixels), "");
    EXPECT_NE(writePngFile((dir / "missing-folder" / "x.png").string(), rgbFile(2, 2)), "");
}

}  // namespace
}  // namespace clipblur
