#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>

#include "renderer/image_module.h"
#include "support/cli_harness.h"

namespace clipblur {
namespace {

ImageFile twoChannelFile() {
    ImageFile f;
    f.full_width = 4;
    f.full_height = 3;
    f.window = PixelBounds::sized(1, 1, 2, 2);
    f.channels = {"R", "Z"};
    f.types = {PixelType::Half, PixelType::Float};
    // Halves of these values are exact (multiples of 1/8 below 2), so they read back bit for bit.
    f.pixels = {0.125f, 1.0e-7f, 0.5f, 3.25f, 1.75f, -2.0f, 0.0f, 1.0e9f};
    f.set(ImageAttribute::string("clipblur:note", "text"));
    f.set(ImageAttribute::integers("clipblur:count", kTypeInt, {-7}));
    f.set(ImageAttribute::floats("clipblur:ratio", kTypeFloat, {0.25f}));
    f.set(ImageAttribute::integers("framesPerSecond", kTypeRational, {24000, 1001}));
    std::vector<float> m(16);
    for (int i = 0; i < 16; ++i) m[static_cast<std::size_t>(i)] = 0.5f * static_cast<float>(i) - 3.0f;
    f.set(ImageAttribute::floats("worldToCamera", kTypeMatrix44, m));
    f.set(ImageAttribute::floats("chromaticities", floatArray(8), {0.64f, 0.33f, 0.3f, 0.6f, 0.15f, 0.06f, 0.3127f, 0.329f}));
    return f;
}

// What the module writes, OpenImageIO reads back directly with the same windows, types and attributes.
TEST(ImageModule, WritesWhatOpenImageIoReadsBack) {
    const auto dir = testing::freshTempDir("clipblur_image_module");
    const std::string path = (dir / "two.exr").string();
    const ImageFile f = twoChannelFile();
    ASSERT_EQ(imageModule().write(path, f), "");
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.full_width, 4);
    EXPECT_EQ(spec.full_height, 3);
    EXPECT_EQ(spec.x, 1);
    EXPECT_EQ(spec.y, 1);
    EXPECT_EQ(spec.channelformat(0), OIIO::TypeDesc::HALF);
    EXPECT_EQ(spec.channelformat(1), OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(spec.get_string_attribute("clipblur:note"), "text");
    EXPECT_EQ(spec.get_int_attribute("clipblur:count"), -7);
    EXPECT_EQ(spec.get_float_attribute("clipblur:ratio"), 0.25f);
    const OIIO::ParamValue* fps = spec.find_attribute("framesPerSecond");
    ASSERT_TRUE(fps);
    EXPECT_EQ(fps->type(), OIIO::TypeRational);
    EXPECT_EQ(static_cast<const int*>(fps->data())[0], 24000);
    EXPECT_EQ(static_cast<const int*>(fps->data())[1], 1001);
    const OIIO::ParamValue* matrix = spec.find_attribute("worldToCamera");
    ASSERT_TRUE(matrix);
    EXPECT_EQ(matrix->type(), OIIO::TypeMatrix44);
    EXPECT_EQ(static_cast<const float*>(matrix->data())[15], 4.5f);
    std::vector<float> pixels(8);
    ASSERT_TRUE(in->read_image(0, 0, 0, 2, OIIO::TypeFloat, pixels.data()));
    EXPECT_EQ(pixels, f.pixels);
}

// Read back through the module, a file equals what was written (attributes as OpenImageIO types them),
// and written again it gives the same file: how a merged frame keeps its shards' headers.
TEST(ImageModule, ReadAndWrittenAgainKeepsEveryAttribute) {
    const auto dir = testing::freshTempDir("clipblur_image_module_again");
    const std::string first = (dir / "first.exr").string(), second = (dir / "second.exr").string();
    ASSERT_EQ(imageModule().write(first, twoChannelFile()), "");
    ImageFile read;
    ASSERT_EQ(imageModule().read(first, ImageRead::HeaderAndPixels, read), "");
    EXPECT_EQ(read.format, "openexr");
    EXPECT_TRUE(read.flat);
    EXPECT_EQ(read.window, PixelBounds::sized(1, 1, 2, 2));
    EXPECT_EQ(read.types, twoChannelFile().types);
    EXPECT_EQ(read.pixels, twoChannelFile().pixels);
    for (const ImageAttribute& want : twoChannelFile().attributes) {
        const ImageAttribute* got = read.find(want.name);
        ASSERT_TRUE(got) << want.name;
        EXPECT_EQ(got->type, want.type) << want.name;
        EXPECT_EQ(got->text, want.text) << want.name;
        EXPECT_EQ(got->bytes, want.bytes) << want.name;
    }
    ASSERT_EQ(imageModule().write(second, read), "");
    ImageFile again;
    ASSERT_EQ(imageModule().read(second, ImageRead::HeaderAndPixels, again), "");
    EXPECT_EQ(again.pixels, read.pixels);
    ASSERT_EQ(again.attributes.size(), read.attributes.size());
    for (const ImageAttribute& a : read.attributes) {
        const ImageAttribute* b = again.find(a.name);
        ASSERT_TRUE(b) << a.name;
        EXPECT_EQ(b->bytes, a.bytes) << a.name;
        EXPECT_EQ(b->text, a.text) << a.name;
    }
}

TEST(ImageModule, MissingAndBrokenFilesGiveTheReason) {
    const auto dir = testing::freshTempDir("clipblur_image_module_bad");
    ImageFile f;
    EXPECT_NE(imageModule().read((dir / "none.exr").string(), ImageRead::Header, f), "");
    std::ofstream((dir / "junk.exr").string()) << "not an image";
    EXPECT_NE(imageModule().read((dir / "junk.exr").string(), ImageRead::Header, f), "");
    ImageFile short_of_pixels = twoChannelFile();
    short_of_pixels.pixels.pop_back();
    EXPECT_NE(imageModule().write((dir / "short.exr").string(), short_of_pixels), "");
    EXPECT_FALSE(std::filesystem::exists(dir / "short.exr"));
}

// The executable does not link OpenImageIO: commands that need neither a texture nor an image format
// other than OpenEXR and PNG never load its dependencies, a render of the default job included.
TEST(ImageModule, VersionValidateAndRenderLoadNoImageLibrary) {
    const std::string binary = CLIPBLUR_BINARY;
    const std::string job = std::string(CLIPBLUR_SOURCE_DIR) + "/configs/default.yaml";
    const auto out = testing::freshTempDir("clipblur_image_module_render") / "tiny.exr";
    const std::string render = binary + " render " + job + " --set film.width=16 --set film.height=9 --progress none --out " +
                               out.string();
    for (const std::string& command : {binary + " --version", binary + " validate " + job, render}) {
        const std::string loaded = testing::captureShell("LD_DEBUG=libs " + command + " 2>&1 >/dev/null");
        EXPECT_NE(loaded.find("libembree3"), std::string::npos) << "LD_DEBUG output not seen for " << command;
        EXPECT_EQ(loaded.find("libOpenImageIO"), std::string::npos) << command;
        EXPECT_EQ(loaded.find("libclipblur_oiio"), std::string::npos) << command;
    }
    EXPECT_TRUE(std::filesystem::exists(out));
    EXPECT_TRUE(std::filesystem::exists(out.parent_path() / "tiny.png"));
}

}  // namespace
}  // namespace clipblur
