#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "clipblur/version.h"
#include "io/image_writer.h"
#include "scene/error.h"
#include "tests/support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

namespace {

// A 5 x 4 data window at (3, 2) inside a 16 x 12 display window; values are multiples of 1/4 so they
// are exact in half precision.
Image windowedImage() {
    Image image;
    image.width = 16;
    image.height = 12;
    image.window = PixelBounds::sized(3, 2, 5, 4);
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
    const fs::path dir = testing::freshTempDir("clipblur_exr_test");
    const Image image = windowedImage();
    for (bool half : {true, false}) {
        const fs::path file = dir / (half ? "half.exr" : "float.exr");
        writeExr(file, image, metadata(), ExrFormat{half, ExrCompression::Zip});
        auto in = OIIO::ImageInput::open(file.string());
        ASSERT_TRUE(in) << OIIO::geterror();
        const OIIO::ImageSpec& spec = in->spec();
        // Half applies to colour and coverage only; depth and motion stay float.
        for (const char* name : {"R", "G", "B", "A", "coverage"})
            EXPECT_EQ(spec.channelformat(channelIndex(spec, name)), half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT)
                << name;
        for (const char* name : {"Z", "motion.x", "motion.y"})
            EXPECT_EQ(spec.channelformat(channelIndex(spec, name)), OIIO::TypeDesc::FLOAT) << name;
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
    const fs::path dir = testing::freshTempDir("clipblur_png_test");
    Image image = windowedImage();
    image.find("R")->values[0] = 0.5f;   // data (0,0) = display (3,2)
    image.find("G")->values[0] = 0.18f;
    image.find("B")->values[0] = 1.0f;
    const fs::path file = dir / "preview.png";
    writePngPreview(file, image, glm::dvec3(0.0));
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
    const fs::path dir = testing::freshTempDir("clipblur_exr_fail_test");
    const fs::path file = dir / "frame.exr";
    writeExr(file, windowedImage(), metadata(), ExrFormat{});
    const auto before = fs::file_size(file);

    Image broken = windowedImage();
    broken.find("G")->values.resize(3);  // inconsistent with the data window: the writer must refuse
    try {
        writeExr(file, broken, metadata(), ExrFormat{false, ExrCompression::Zip});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Output);
    }
    EXPECT_EQ(fs::file_size(file), before);
    auto in = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().channelformat(channelIndex(in->spec(), "R")), OIIO::TypeDesc::HALF);  // still the first file
    EXPECT_TRUE(noTemporaries(dir));

    // A target whose folder cannot be created (a regular file is in the way) fails the same way.
    std::ofstream(dir / "blocker") << "x";
    EXPECT_THROW(writeExr(dir / "blocker" / "frame.exr", windowedImage(), metadata(), ExrFormat{}), Error);
}

namespace {

// Output of a shell command (stdout), for OpenEXR's own tools.
FrameHeader sampleFrameHeader() {
    FrameHeader h;
    h.frame = 7;
    h.fps_numerator = 24000;
    h.fps_denominator = 1001;
    h.shutter_open = 0.25;
    h.shutter_close = 0.75;
    h.exposure_seconds = 0.5 / 24.0;
    for (std::size_t i = 0; i < 16; ++i) {
        h.world_to_camera[i] = static_cast<float>(i) + 0.5f;
        h.world_to_ndc[i] = static_cast<float>(0 - static_cast<int>(i));  // no -0 (exrheader prints it)
    }
    return h;
}

}  // namespace

TEST(ImageWriter, HeaderCarriesCompressionChromaticitiesAndTheFrame) {
    const fs::path dir = testing::freshTempDir("clipblur_exr_header_test");
    ImageMetadata meta = metadata();
    meta.frame = sampleFrameHeader();
    for (const ExrCompression compression :
         {ExrCompression::Zip, ExrCompression::Piz, ExrCompression::Dwaa, ExrCompression::None}) {
        const std::string name = compressionName(compression);
        const fs::path file = dir / (name + ".exr");
        writeExr(file, windowedImage(), meta, ExrFormat{true, compression});
        auto in = OIIO::ImageInput::open(file.string());
        ASSERT_TRUE(in) << OIIO::geterror();
        const OIIO::ImageSpec& spec = in->spec();
        EXPECT_EQ(spec.get_string_attribute("compression").substr(0, name.size()), name);
        const OIIO::ParamValue* chroma = spec.find_attribute("chromaticities");
        ASSERT_TRUE(chroma) << name;
        ASSERT_EQ(chroma->type(), OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8));
        const float* xy = static_cast<const float*>(chroma->data());
        // ITU-R BT.709 primaries and the D65 white point.
        const float rec709[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
        for (int i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(xy[i], rec709[i]) << i;
        const OIIO::ParamValue* fps = spec.find_attribute("framesPerSecond");
        ASSERT_TRUE(fps);
        EXPECT_EQ(fps->type(), OIIO::TypeRational);
        EXPECT_EQ(static_cast<const int*>(fps->data())[0], 24000);
        EXPECT_EQ(static_cast<const int*>(fps->data())[1], 1001);
        for (const char* key : {"worldToCamera", "worldToNDC"}) {
            const OIIO::ParamValue* m = spec.find_attribute(key);
            ASSERT_TRUE(m) << key;
            ASSERT_EQ(m->type(), OIIO::TypeMatrix44) << key;
            const float* v = static_cast<const float*>(m->data());
            const ExrMatrix& want = std::string(key) == "worldToNDC" ? meta.frame->world_to_ndc : meta.frame->world_to_camera;
            for (std::size_t i = 0; i < 16; ++i) EXPECT_EQ(v[i], want[i]) << key << " " << i;
        }
        EXPECT_EQ(spec.get_int_attribute("clipblur:frame"), 7);
        EXPECT_FLOAT_EQ(spec.get_float_attribute("clipblur:shutterOpen"), 0.25f);
        EXPECT_FLOAT_EQ(spec.get_float_attribute("clipblur:shutterClose"), 0.75f);
        EXPECT_FLOAT_EQ(spec.get_float_attribute("ExposureTime"), 0.5f / 24.0f);
        EXPECT_EQ(spec.get_string_attribute("Software"), std::string("clipblur ") + kVersion);
    }
}

// OpenEXR's own reader, not OpenImageIO's mapping of it, must see the standard attributes and the
// per-channel types (installed by scripts/setup.sh from Debian's openexr).
TEST(ImageWriter, ExrheaderSeesStandardAttributesAndFloatDepth) {
    if (std::system("command -v exrheader > /dev/null 2>&1") != 0) GTEST_SKIP() << "exrheader (Debian openexr) missing";
    const fs::path dir = testing::freshTempDir("clipblur_exrheader_test");
    ImageMetadata meta = metadata();
    meta.frame = sampleFrameHeader();
    const fs::path file = dir / "piz.exr";
    writeExr(file, windowedImage(), meta, ExrFormat{true, ExrCompression::Piz});
    const std::string text = testing::captureShell("exrheader " + file.string());
    // exrheader's own spelling of each attribute; the standard names are OpenEXR's, not OpenImageIO's.
    const char* lines[] = {"framesPerSecond (type rational): 24000/1001",
                           "expTime (type float):",
                           "compression (type compression): piz",
                           "chromaticities (type chromaticities):\n    red   (0.64 0.33)\n    green (0.3 0.6)\n"
                           "    blue  (0.15 0.06)\n    white (0.3127 0.329)",
                           "worldToCamera (type m44f):\n   (0.5 1.5 2.5 3.5",
                           "worldToNDC (type m44f):\n   (0 -1 -2 -3",
                           "    R, 16-bit floating-point",
                           "    A, 16-bit floating-point",
                           "    Z, 32-bit floating-point",
                           "    motion.x, 32-bit floating-point",
                           "    motion.y, 32-bit floating-point",
                           "clipblur:frame (type int): 7"};
    for (const char* expected : lines) EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
}

}  // namespace clipblur
