#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "io/exr_file.h"
#include "io/image_files.h"
#include "tests/support/cli_harness.h"

namespace clipblur {
namespace {

// A 3 x 2 data window at (1, 1) of a 5 x 4 display window, channels in the order a render gives them
// (colour, an AOV, a layer whose name sorts before it), half and float. The values are multiples of
// 1/8 below 2 where half, so they read back bit for bit.
ImageFile layeredFile() {
    ImageFile f;
    f.full_width = 5;
    f.full_height = 4;
    f.window = PixelBounds::sized(1, 1, 3, 2);
    f.channels = {"R", "G", "B", "A", "Z", "forward.u", "Crypto00.R", "Crypto00.A"};
    f.types = {PixelType::Half, PixelType::Half, PixelType::Half, PixelType::Half,
               PixelType::Float, PixelType::Float, PixelType::Float, PixelType::Float};
    for (std::size_t i = 0; i < 6; ++i)
        for (std::size_t c = 0; c < f.channels.size(); ++c)
            f.pixels.push_back(c < 4 ? 0.125f * static_cast<float>(i + c) : 1.0e-7f * static_cast<float>(i) - 3.0f * c);
    f.set(ImageAttribute::string("compression", "piz"));
    f.set(ImageAttribute::string("clipblur:note", "text"));
    f.set(ImageAttribute::integers("clipblur:count", kTypeInt, {-7}));
    f.set(ImageAttribute::floats("expTime", kTypeFloat, {0.25f}));
    f.set(ImageAttribute::integers("framesPerSecond", kTypeRational, {24000, 1001}));
    std::vector<float> m(16);
    for (int i = 0; i < 16; ++i) m[static_cast<std::size_t>(i)] = 0.5f * static_cast<float>(i) - 3.0f;
    f.set(ImageAttribute::floats("worldToCamera", kTypeMatrix44, m));
    f.set(ImageAttribute::floats("chromaticities", floatArray(8), {0.64f, 0.33f, 0.3f, 0.6f, 0.15f, 0.06f, 0.3127f, 0.329f}));
    return f;
}

std::vector<float> channelOf(const ImageFile& f, const std::string& name) {
    const auto it = std::find(f.channels.begin(), f.channels.end(), name);
    const std::size_t c = static_cast<std::size_t>(it - f.channels.begin()), nc = f.channels.size();
    std::vector<float> v;
    for (std::size_t i = c; i < f.pixels.size(); i += nc) v.push_back(f.pixels[i]);
    return v;
}

// OpenImageIO, an independent reader, sees what OpenEXR wrote: windows, types, attributes under their
// OpenImageIO names, pixels bit for bit.
TEST(ExrFile, WritesWhatOpenImageIoReadsBack) {
    const auto dir = testing::freshTempDir("clipblur_exr_file");
    const std::string path = (dir / "layered.exr").string();
    const ImageFile f = layeredFile();
    ASSERT_EQ(writeExrFile(path, f), "");
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.full_width, 5);
    EXPECT_EQ(spec.full_height, 4);
    EXPECT_EQ(spec.x, 1);
    EXPECT_EQ(spec.y, 1);
    EXPECT_EQ(spec.width, 3);
    EXPECT_EQ(spec.height, 2);
    EXPECT_EQ(spec.get_string_attribute("compression"), "piz");
    EXPECT_EQ(spec.get_string_attribute("clipblur:note"), "text");
    EXPECT_EQ(spec.get_int_attribute("clipblur:count"), -7);
    EXPECT_EQ(spec.get_float_attribute("ExposureTime"), 0.25f);  // OpenImageIO's name for expTime
    const OIIO::ParamValue* fps = spec.find_attribute("framesPerSecond");
    ASSERT_TRUE(fps);
    EXPECT_EQ(fps->type(), OIIO::TypeRational);
    EXPECT_EQ(static_cast<const int*>(fps->data())[0], 24000);
    EXPECT_EQ(static_cast<const int*>(fps->data())[1], 1001);
    const OIIO::ParamValue* matrix = spec.find_attribute("worldToCamera");
    ASSERT_TRUE(matrix);
    EXPECT_EQ(matrix->type(), OIIO::TypeMatrix44);
    EXPECT_EQ(static_cast<const float*>(matrix->data())[15], 4.5f);
    std::vector<float> pixels(static_cast<std::size_t>(spec.width * spec.height * spec.nchannels));
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeFloat, pixels.data()));
    for (int c = 0; c < spec.nchannels; ++c) {
        const std::string name = spec.channelnames[static_cast<std::size_t>(c)];
        const bool colour = name.size() == 1 && std::string("RGBA").find(name) != std::string::npos;
        EXPECT_EQ(spec.channelformat(c), colour ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT) << name;
        std::vector<float> got;
        for (std::size_t i = static_cast<std::size_t>(c); i < pixels.size(); i += static_cast<std::size_t>(spec.nchannels))
            got.push_back(pixels[i]);
        EXPECT_EQ(got, channelOf(f, name)) << name;
    }
}

// A file OpenImageIO wrote reads with the channels in the order OpenImageIO's own reader gives them,
// the same values, and the attributes both know.
TEST(ExrFile, ReadsOpenImageIoFilesAsOpenImageIoDoes) {
    const auto dir = testing::freshTempDir("clipblur_exr_file_oiio");
    const std::string path = (dir / "oiio.exr").string();
    const std::vector<std::string> names = {"forward.v", "Z", "Crypto00.A", "A", "coverage", "B", "Crypto00.R",
                                            "G", "R", "forward.u", "Crypto01.G"};
    const int nc = static_cast<int>(names.size());
    OIIO::ImageSpec spec(4, 3, nc, OIIO::TypeDesc::FLOAT);
    spec.channelnames = names;
    spec.attribute("clipblur:note", "from OpenImageIO");
    std::vector<float> pixels(static_cast<std::size_t>(4 * 3 * nc));
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = 0.5f * static_cast<float>(i) - 7.0f;
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());

    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    std::vector<float> theirs(pixels.size());
    ASSERT_TRUE(in->read_image(0, 0, 0, nc, OIIO::TypeFloat, theirs.data()));
    ImageFile ours;
    ASSERT_EQ(readExrFile(path, ImageRead::HeaderAndPixels, ours), "");
    EXPECT_EQ(ours.format, "openexr");
    EXPECT_EQ(ours.channels, in->spec().channelnames);
    EXPECT_EQ(ours.pixels, theirs);
    EXPECT_EQ(ours.window, PixelBounds::sized(0, 0, 4, 3));
    EXPECT_EQ(ours.stringAttribute("clipblur:note"), "from OpenImageIO");
}

// Read back, a file equals what was written, and written again it gives the same header: how a merged
// frame keeps its shards' headers.
TEST(ExrFile, ReadAndWrittenAgainKeepsEveryAttribute) {
    const auto dir = testing::freshTempDir("clipblur_exr_file_again");
    const std::string first = (dir / "first.exr").string(), second = (dir / "second.exr").string();
    const ImageFile f = layeredFile();
    ASSERT_EQ(writeExrFile(first, f), "");
    ImageFile read;
    ASSERT_EQ(readExrFile(first, ImageRead::HeaderAndPixels, read), "");
    EXPECT_EQ(read.full_width, 5);
    EXPECT_EQ(read.window, f.window);
    for (const std::string& name : f.channels) EXPECT_EQ(channelOf(read, name), channelOf(f, name)) << name;
    for (const ImageAttribute& want : f.attributes) {
        const ImageAttribute* got = read.find(want.name);
        ASSERT_TRUE(got) << want.name;
        EXPECT_EQ(got->type, want.type) << want.name;
        EXPECT_EQ(got->text, want.text) << want.name;
        EXPECT_EQ(got->bytes, want.bytes) << want.name;
    }
    EXPECT_EQ(read.attributes.size(), f.attributes.size());
    ASSERT_EQ(writeExrFile(second, read), "");
    ImageFile again;
    ASSERT_EQ(readExrFile(second, ImageRead::HeaderAndPixels, again), "");
    EXPECT_EQ(again.channels, read.channels);
    EXPECT_EQ(again.types, read.types);
    EXPECT_EQ(again.pixels, read.pixels);
    ASSERT_EQ(again.attributes.size(), read.attributes.size());
    for (std::size_t i = 0; i < read.attributes.size(); ++i) {
        EXPECT_EQ(again.attributes[i].name, read.attributes[i].name);
        EXPECT_EQ(again.attributes[i].bytes, read.attributes[i].bytes);
        EXPECT_EQ(again.attributes[i].text, read.attributes[i].text);
    }
}

TEST(ExrFile, MissingBrokenAndCutShortFilesGiveTheReason) {
    const auto dir = testing::freshTempDir("clipblur_exr_file_bad");
    ImageFile f;
    EXPECT_NE(readExrFile((dir / "none.exr").string(), ImageRead::Header, f), "");
    EXPECT_TRUE(f.format.empty());
    std::ofstream((dir / "junk.exr").string()) << "not an image";
    EXPECT_NE(readExrFile((dir / "junk.exr").string(), ImageRead::Header, f), "");
    EXPECT_TRUE(f.format.empty());

    const std::string whole = (dir / "whole.exr").string(), cut = (dir / "cut.exr").string();
    ImageFile big = layeredFile();
    big.set(ImageAttribute::string("compression", "none"));
    ASSERT_EQ(writeExrFile(whole, big), "");
    const auto size = std::filesystem::file_size(whole);
    std::filesystem::copy_file(whole, cut);
    std::filesystem::resize_file(cut, size - 8);
    EXPECT_EQ(readExrFile(cut, ImageRead::Header, f), "");
    EXPECT_NE(readExrFile(cut, ImageRead::HeaderAndPixels, f), "");
    EXPECT_EQ(f.format, "openexr");  // the header is intact
    EXPECT_EQ(f.window, big.window);

    ImageFile short_of_pixels = layeredFile();
    short_of_pixels.pixels.pop_back();
    EXPECT_NE(writeExrFile((dir / "short.exr").string(), short_of_pixels), "");
    EXPECT_FALSE(std::filesystem::exists(dir / "short.exr"));
    ImageFile unknown = layeredFile();
    unknown.set(ImageAttribute::string("compression", "best"));
    EXPECT_NE(writeExrFile((dir / "unknown.exr").string(), unknown), "");
    // A small image stays in the stream's buffer until the close, so only the close sees the full disk.
    if (std::filesystem::exists("/dev/full")) {
        EXPECT_NE(writeExrFile("/dev/full", layeredFile()), "");
    }
}

// EXR goes to OpenEXR by its name or, whatever its name, by its first bytes.
TEST(ImageFiles, OpenExrFilesAreKnownByExtensionOrMagicNumber) {
    const auto dir = testing::freshTempDir("clipblur_image_files");
    const std::string named = (dir / "frame.EXR").string(), unnamed = (dir / "frame.bin").string();
    ASSERT_EQ(writeImageFile(named, layeredFile()), "");
    std::filesystem::copy_file(named, unnamed);
    ImageFile a, b;
    ASSERT_EQ(readImageFile(named, ImageRead::HeaderAndPixels, a), "");
    ASSERT_EQ(readImageFile(unnamed, ImageRead::HeaderAndPixels, b), "");
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(a.channels, b.channels);
}

// Every other format goes through the image module, and a PNG written by libpng reads back through it:
// the paths a `--reference photo.png` or an `--out frame.tif` take.
TEST(ImageFiles, OtherFormatsGoThroughTheImageModule) {
    const auto dir = testing::freshTempDir("clipblur_image_files_other");
    ImageFile f;
    f.full_width = 3;
    f.full_height = 2;
    f.window = PixelBounds::sized(0, 0, 3, 2);
    f.channels = {"R", "G", "B"};
    f.types.assign(3, PixelType::Float);
    for (int i = 0; i < 18; ++i) f.pixels.push_back(0.25f * static_cast<float>(i) - 1.0f);
    const std::string tif = (dir / "frame.tif").string();
    ASSERT_EQ(writeImageFile(tif, f), "");
    ImageFile back;
    ASSERT_EQ(readImageFile(tif, ImageRead::HeaderAndPixels, back), "");
    EXPECT_EQ(back.pixels, f.pixels);
    ImageFile codes = f;
    codes.types.assign(3, PixelType::UInt8);
    for (std::size_t i = 0; i < codes.pixels.size(); ++i) codes.pixels[i] = static_cast<float>(i * 13) / 255.0f;
    const std::string png = (dir / "preview.png").string();
    ASSERT_EQ(writeImageFile(png, codes), "");
    ASSERT_EQ(readImageFile(png, ImageRead::HeaderAndPixels, back), "");
    ASSERT_EQ(back.pixels.size(), codes.pixels.size());
    for (std::size_t i = 0; i < codes.pixels.size(); ++i) EXPECT_EQ(std::lround(back.pixels[i] * 255.0f), static_cast<long>(i * 13)) << i;
    EXPECT_NE(readImageFile((dir / "missing.png").string(), ImageRead::Header, back), "");
}

}  // namespace
}  // namespace clipblur
