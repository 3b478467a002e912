#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "clipblur/version.h"
#include "io/image_writer.h"
#include "scene/error.h"

namespace clipblur {

namespace fs = std::filesystem;

namespace {

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// A 5 x 4 data window at (3, 2) inside a 16 x 12 display window; values are multiples of 1/4 so they
// are exact in half precision.
Image windowedImage() {
    Image image;
    image.width = 16;
    image.height = 12;
    image.x0 = 3;
    image.y0 = 2;
    image.data_width = 5;
    image.data_height = 4;
    const char* names[] = {"R", "G", "B", "A", "Z", "coverage", "motion.x", "motion.y"};
    for (int c = 0; c < 8; ++c) {
        Image::Channel channel{names[c], std::vector<float>(20)};
        for (int i = 0; i < 20; ++i) channel.values[static_cast<std::size_t>(i)] = 0.25f * (i + c);
        image.channels.push_back(channel);
    }
    return image;
}

ImageMetadata metadata() {
    ImageMetadata m;
    m.method = "stochastic";
    m.samples = 64;
    m.seed = 18446744073709551615ULL;
    m.config_hash = "abc123";
    m.render_seconds = 1.5;
    return m;
}

int channelIndex(const OIIO::ImageSpec& spec, const std::string& name) {
    for (int c = 0; c < spec.nchannels; ++c)
        if (spec.channelnames[static_cast<std::size_t>(c)] == name) return c;
    return -1;
}

bool noTemporaries(const fs::path& dir) {
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().filename().string().rfind(".tmp-", 0) == 0) return false;
    return true;
}

}  // namespace

TEST(ImageWriter, ExrRoundTripKeepsChannelsWindowsAndMetadata) {
    const fs::path dir = freshDir("clipblur_exr_test");
    const Image image = windowedImage();
    for (bool half : {true, false}) {
        const fs::path file = dir / (half ? "half.exr" : "float.exr");
        writeExr(file, image, metadata(), half);
        auto in = OIIO::ImageInput::open(file.string());
        ASSERT_TRUE(in) << OIIO::geterror();
        const OIIO::ImageSpec& spec = in->spec();
        EXPECT_EQ(spec.format, half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
        EXPECT_EQ(spec.x, 3);
        EXPECT_EQ(spec.y, 2);
        EXPECT_EQ(spec.width, 5);
        EXPECT_EQ(spec.height, 4);
        EXPECT_EQ(spec.full_x, 0);
        EXPECT_EQ(spec.full_y, 0);
        EXPECT_EQ(spec.full_width, 16);
        EXPECT_EQ(spec.full_height, 12);
        ASSERT_EQ(spec.nchannels, 8);
        EXPECT_EQ(spec.get_string_attribute("clipblur:version"), kVersion);
        EXPECT_EQ(spec.get_string_attribute("clipblur:git"), kGitHash);
        EXPECT_EQ(spec.get_string_attribute("clipblur:method"), "stochastic");
        EXPECT_EQ(spec.get_int_attribute("clipblur:samples"), 64);
        EXPECT_EQ(spec.get_int_attribute("clipblur:subframes", -7), -7);  // not given, not written
        EXPECT_EQ(spec.get_string_attribute("clipblur:seed"), "18446744073709551615");
        EXPECT_EQ(spec.get_string_attribute("clipblur:configHash"), "abc123");
        EXPECT_FLOAT_EQ(spec.get_float_attribute("clipblur:renderSeconds"), 1.5f);

        std::vector<float> pixels(20 * 8);
        ASSERT_TRUE(in->read_image(0, 0, 0, 8, OIIO::TypeDesc::FLOAT, pixels.data()));
        // The file may order channels differently (EXR sorts them); compare by name.
        for (const auto& channel : image.channels) {
            const int c = channelIndex(spec, channel.name);
            ASSERT_GE(c, 0) << channel.name;
            for (int i = 0; i < 20; ++i)
                EXPECT_EQ(pixels[static_cast<std::size_t>(i * 8 + c)], channel.values[static_cast<std::size_t>(i)])
                    << channel.name << " " << i;
        }
    }
}

TEST(ImageWriter, SrgbEncodingMatchesTheStandardCurve) {
    // Hand values of 255 * (12.92 v) below 0.0031308, else 255 * (1.055 v^(1/2.4) - 0.055), rounded.
    EXPECT_EQ(encodeSrgb8(0.0f), 0);
    EXPECT_EQ(encodeSrgb8(1.0f), 255);
    EXPECT_EQ(encodeSrgb8(4.0f), 255);
    EXPECT_EQ(encodeSrgb8(-1.0f), 0);
    EXPECT_EQ(encodeSrgb8(0.002f), 7);    // 6.59
    EXPECT_EQ(encodeSrgb8(0.18f), 118);   // 117.65
    EXPECT_EQ(encodeSrgb8(0.5f), 188);    // 187.52
    EXPECT_EQ(encodeSrgb8(0.75f), 225);   // 224.61
}

TEST(ImageWriter, PngPreviewCoversTheDisplayWindow) {
    const fs::path dir = freshDir("clipblur_png_test");
    Image image = windowedImage();
    image.find("R")->values[0] = 0.5f;   // data (0,0) = display (3,2)
    image.find("G")->values[0] = 0.18f;
    image.find("B")->values[0] = 1.0f;
    const fs::path file = dir / "preview.png";
    writePngPreview(file, image);
    auto in = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec spec = in->spec();
    EXPECT_EQ(spec.width, 16);
    EXPECT_EQ(spec.height, 12);
    ASSERT_EQ(spec.nchannels, 3);
    std::vector<std::uint8_t> pixels(16 * 12 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pixels.data()));
    const std::size_t at = (2 * 16 + 3) * 3;
    EXPECT_EQ(pixels[at + 0], 188);
    EXPECT_EQ(pixels[at + 1], 118);
    EXPECT_EQ(pixels[at + 2], 255);
    EXPECT_EQ(pixels[0], 0);  // outside the data window
}

TEST(ImageWriter, FailedWriteLeavesThePreviousFile) {
    const fs::path dir = freshDir("clipblur_exr_fail_test");
    const fs::path file = dir / "frame.exr";
    writeExr(file, windowedImage(), metadata(), true);
    const auto before = fs::file_size(file);

    Image broken = windowedImage();
    broken.find("G")->values.resize(3);  // inconsistent with the data window: the writer must refuse
    try {
        writeExr(file, broken, metadata(), false);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Output);
    }
    EXPECT_EQ(fs::file_size(file), before);
    auto in = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::HALF);  // still the first, half-float file
    EXPECT_TRUE(noTemporaries(dir));

    // A target whose folder cannot be created (a regular file is in the way) fails the same way.
    std::ofstream(dir / "blocker") << "x";
    EXPECT_THROW(writeExr(dir / "blocker" / "frame.exr", windowedImage(), metadata(), true), Error);
}

}  // namespace clipblur
