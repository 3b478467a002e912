#include "io/exr_file.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <exception>
#include <fstream>
#include <set>
#include <string_view>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfChromaticitiesAttribute.h>
#include <OpenEXR/ImfCompressionAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFloatVectorAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfRationalAttribute.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfStringVectorAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfVecAttribute.h>
#include <Imath/half.h>

#include "renderer/worker_threads.h"

namespace clipblur {

namespace {

constexpr std::array<std::pair<std::string_view, Imf::Compression>, 10> kCompressions{{
    {"none", Imf::NO_COMPRESSION},
    {"rle", Imf::RLE_COMPRESSION},
    {"zips", Imf::ZIPS_COMPRESSION},
    {"zip", Imf::ZIP_COMPRESSION},
    {"piz", Imf::PIZ_COMPRESSION},
    {"pxr24", Imf::PXR24_COMPRESSION},
    {"b44", Imf::B44_COMPRESSION},
    {"b44a", Imf::B44A_COMPRESSION},
    {"dwaa", Imf::DWAA_COMPRESSION},
    {"dwab", Imf::DWAB_COMPRESSION},
}};

// Header entries that ImageFile's fields carry, or that every clipblur file has at its default.
const std::set<std::string_view> kStructural{"channels",           "dataWindow",        "displayWindow",
                                             "lineOrder",          "pixelAspectRatio",  "screenWindowCenter",
                                             "screenWindowWidth",  "type",              "compression",
                                             "chunkCount",         "version",           "name"};

constexpr AttributeType kTypeVec2f{kBaseFloat, 2, 0}, kTypeVec3f{kBaseFloat, 3, 0}, kTypeVec2i{kBaseInt32, 2, 0};

template <class T>
std::vector<T> valuesOf(const ImageAttribute& a) {
    std::vector<T> v(a.bytes.size() / sizeof(T));
    if (!v.empty()) std::memcpy(v.data(), a.bytes.data(), v.size() * sizeof(T));
    return v;
}

template <class T>
ImageAttribute withBytes(const std::string& name, AttributeType type, const T* values, std::size_t n) {
    ImageAttribute a{name, type, {}, {}};
    const auto* bytes = reinterpret_cast<const unsigned char*>(values);
    a.bytes.assign(bytes, bytes + n * sizeof(T));
    return a;
}

// Adds `a` to `header`; empty on success, else why not.
std::string addAttribute(Imf::Header& header, const ImageAttribute& a) {
    const AttributeType& t = a.type;
    const std::size_t floats = a.bytes.size() / sizeof(float);
    if (a.name == "compression") {
        const std::string value = t == kTypeString && a.text.size() == 1 ? a.text.front() : std::string();
        const auto it = std::find_if(kCompressions.begin(), kCompressions.end(),
                                     [&](const auto& c) { return c.first == value; });
        if (it == kCompressions.end()) return "unknown OpenEXR compression '" + value + "'";
        header.compression() = it->second;
    } else if (t.base == kBaseString) {
        if (a.text.size() == 1 && t.array == 0)
            header.insert(a.name, Imf::StringAttribute(a.text.front()));
        else
            header.insert(a.name, Imf::StringVectorAttribute(a.text));
    } else if (t == kTypeInt && a.bytes.size() == sizeof(int)) {
        header.insert(a.name, Imf::IntAttribute(valuesOf<int>(a).front()));
    } else if (t == kTypeFloat && floats == 1) {
        header.insert(a.name, Imf::FloatAttribute(valuesOf<float>(a).front()));
    } else if (t == kTypeMatrix44 && floats == 16) {
        const std::vector<float> m = valuesOf<float>(a);
        header.insert(a.name, Imf::M44fAttribute(Imath::M44f(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8],
                                                              m[9], m[10], m[11], m[12], m[13], m[14], m[15])));
    } else if (t == kTypeRational && a.bytes.size() == 2 * sizeof(int)) {
        const std::vector<int> r = valuesOf<int>(a);
        if (r[1] < 0) return "attribute " + a.name + " has a negative denominator";
        header.insert(a.name, Imf::RationalAttribute(Imf::Rational(r[0], static_cast<unsigned>(r[1]))));
    } else if (a.name == "chromaticities" && t == floatArray(8) && floats == 8) {
        const std::vector<float> c = valuesOf<float>(a);
        header.insert(a.name, Imf::ChromaticitiesAttribute(Imf::Chromaticities(
                                  {c[0], c[1]}, {c[2], c[3]}, {c[4], c[5]}, {c[6], c[7]})));
    } else if (t == kTypeVec2f && floats == 2) {
        const std::vector<float> v = valuesOf<float>(a);
        header.insert(a.name, Imf::V2fAttribute(Imath::V2f(v[0], v[1])));
    } else if (t == kTypeVec3f && floats == 3) {
        const std::vector<float> v = valuesOf<float>(a);
        header.insert(a.name, Imf::V3fAttribute(Imath::V3f(v[0], v[1], v[2])));
    } else if (t == kTypeVec2i && a.bytes.size() == 2 * sizeof(int)) {
        const std::vector<int> v = valuesOf<int>(a);
        header.insert(a.name, Imf::V2iAttribute(Imath::V2i(v[0], v[1])));
    } else if (t.base == kBaseFloat && t.aggregate == 1 && t.array > 0 &&
               floats == static_cast<std::size_t>(t.array)) {
        header.insert(a.name, Imf::FloatVectorAttribute(valuesOf<float>(a)));
    } else {
        return "attribute " + a.name + " has a type OpenEXR files cannot hold here";
    }
    return {};
}

// `attribute` as an ImageAttribute; false for types clipblur has no use for (left out).
bool attributeOf(const std::string& name, const Imf::Attribute& attribute, ImageAttribute& out) {
    if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&attribute)) {
        out = ImageAttribute::string(name, s->value());
    } else if (const auto* sv = dynamic_cast<const Imf::StringVectorAttribute*>(&attribute)) {
        out = {name, {kBaseString, 1, 0, static_cast<int>(sv->value().size())}, sv->value(), {}};
    } else if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&attribute)) {
        out = ImageAttribute::integers(name, kTypeInt, {i->value()});
    } else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&attribute)) {
        out = ImageAttribute::floats(name, kTypeFloat, {f->value()});
    } else if (const auto* m = dynamic_cast<const Imf::M44fAttribute*>(&attribute)) {
        out = withBytes(name, kTypeMatrix44, m->value().getValue(), 16);
    } else if (const auto* r = dynamic_cast<const Imf::RationalAttribute*>(&attribute)) {
        out = ImageAttribute::integers(name, kTypeRational, {r->value().n, static_cast<int>(r->value().d)});
    } else if (const auto* c = dynamic_cast<const Imf::ChromaticitiesAttribute*>(&attribute)) {
        const Imf::Chromaticities& v = c->value();
        out = ImageAttribute::floats(name, floatArray(8), {v.red.x, v.red.y, v.green.x, v.green.y, v.blue.x,
                                                            v.blue.y, v.white.x, v.white.y});
    } else if (const auto* v2 = dynamic_cast<const Imf::V2fAttribute*>(&attribute)) {
        out = ImageAttribute::floats(name, kTypeVec2f, {v2->value().x, v2->value().y});
    } else if (const auto* v3 = dynamic_cast<const Imf::V3fAttribute*>(&attribute)) {
        out = ImageAttribute::floats(name, kTypeVec3f, {v3->value().x, v3->value().y, v3->value().z});
    } else if (const auto* i2 = dynamic_cast<const Imf::V2iAttribute*>(&attribute)) {
        out = ImageAttribute::integers(name, kTypeVec2i, {i2->value().x, i2->value().y});
    } else if (const auto* fv = dynamic_cast<const Imf::FloatVectorAttribute*>(&attribute)) {
        out = ImageAttribute::floats(name, floatArray(static_cast<int>(fv->value().size())), fv->value());
    } else {
        return false;
    }
    return true;
}

// OpenImageIO's reading order (so that files read alike through either): channels without a layer, then
// each layer by name; within one, R, G, B, A first, the rest in the file's (alphabetical) order.
std::vector<std::string> readingOrder(const Imf::ChannelList& list) {
    struct Entry {
        std::string layer;
        int rank;
        int index;
        std::string name;
    };
    std::vector<Entry> entries;
    for (auto it = list.begin(); it != list.end(); ++it) {
        const std::string name = it.name();
        const std::size_t dot = name.rfind('.');
        const std::string layer = dot == std::string::npos ? std::string() : name.substr(0, dot);
        const std::string suffix = dot == std::string::npos ? name : name.substr(dot + 1);
        static constexpr std::array<std::string_view, 4> kFirst{"R", "G", "B", "A"};
        const auto first = std::find(kFirst.begin(), kFirst.end(), suffix);
        entries.push_back({layer, static_cast<int>(first - kFirst.begin()), static_cast<int>(entries.size()), name});
    }
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
        return std::tie(a.layer, a.rank, a.index) < std::tie(b.layer, b.rank, b.index);
    });
    std::vector<std::string> names;
    for (const Entry& e : entries) names.push_back(e.name);
    return names;
}

PixelType pixelType(Imf::PixelType t) { return t == Imf::HALF ? PixelType::Half : PixelType::Float; }

ImageFile describe(const Imf::Header& header) {
    ImageFile f;
    f.format = "openexr";
    const Imath::Box2i& display = header.displayWindow();
    const Imath::Box2i& data = header.dataWindow();
    f.full_x = display.min.x;
    f.full_y = display.min.y;
    f.full_width = display.max.x - display.min.x + 1;
    f.full_height = display.max.y - display.min.y + 1;
    f.window = PixelBounds::corners(data.min.x, data.min.y, data.max.x + 1, data.max.y + 1);
    // A deep file reads composited; it is never one of ours, which the shard checks must see.
    f.flat = !(header.hasType() && Imf::isDeepData(header.type()));
    for (const std::string& name : readingOrder(header.channels())) {
        f.channels.push_back(name);
        f.types.push_back(pixelType(header.channels().find(name).channel().type));
    }
    const auto compression = std::find_if(kCompressions.begin(), kCompressions.end(),
                                          [&](const auto& c) { return c.second == header.compression(); });
    if (compression != kCompressions.end())
        f.attributes.push_back(ImageAttribute::string("compression", std::string(compression->first)));
    for (auto it = header.begin(); it != header.end(); ++it) {
        ImageAttribute a;
        if (!kStructural.count(it.name()) && attributeOf(it.name(), it.attribute(), a))
            f.attributes.push_back(std::move(a));
    }
    return f;
}

// Interleaved float pixels of a data window as one slice per channel, to read into.
Imf::FrameBuffer readBuffer(const Imath::Box2i& data, const std::vector<std::string>& channels, float* pixels) {
    Imf::FrameBuffer fb;
    const std::size_t nc = channels.size();
    const std::size_t width = static_cast<std::size_t>(data.max.x - data.min.x + 1);
    for (std::size_t c = 0; c < nc; ++c)
        fb.insert(channels[c], Imf::Slice::Make(Imf::FLOAT, pixels + c, data, nc * sizeof(float),
                                                nc * sizeof(float) * width));
    return fb;
}

// The slices to write `image` from: float channels in place, half ones (which OpenEXR takes only as
// half) rounded to the nearest half into `halves`, one plane per channel.
Imf::FrameBuffer writeBuffer(const Imath::Box2i& data, const ImageFile& image, std::vector<half>& halves) {
    Imf::FrameBuffer fb;
    const std::size_t nc = image.channels.size();
    const std::size_t n = image.window.area();
    const std::size_t width = static_cast<std::size_t>(image.window.width());
    const auto planes = static_cast<std::size_t>(std::count(image.types.begin(), image.types.end(), PixelType::Half));
    halves.assign(planes * n, half());
    std::size_t plane = 0;
    for (std::size_t c = 0; c < nc; ++c) {
        if (image.types[c] == PixelType::Float) {
            fb.insert(image.channels[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, data,
                                                          nc * sizeof(float), nc * sizeof(float) * width));
            continue;
        }
        half* out = halves.data() + plane++ * n;
        for (std::size_t i = 0; i < n; ++i) out[i] = half(image.pixels[i * nc + c]);
        fb.insert(image.channels[c], Imf::Slice::Make(Imf::HALF, out, data, sizeof(half), sizeof(half) * width));
    }
    return fb;
}

// OpenEXR compresses on its own threads, as many as the render may use (bits do not depend on them).
void useRenderThreads() {
    const int threads = workerThreads();
    if (Imf::globalThreadCount() != threads) Imf::setGlobalThreadCount(threads);
}

}  // namespace

std::string readExrFile(const std::string& file, ImageRead what, ImageFile& out) {
    out = ImageFile{};
    try {
        useRenderThreads();
        Imf::InputFile in(file.c_str());
        out = describe(in.header());
        if (what == ImageRead::Header) return {};
        // Reading every pixel is the only reliable test for a file cut short: the header of a truncated
        // EXR is intact, its missing chunks only show when read.
        out.pixels.assign(out.window.area() * out.channels.size(), 0.0f);
        const Imath::Box2i& data = in.header().dataWindow();
        in.setFrameBuffer(readBuffer(data, out.channels, out.pixels.data()));
        in.readPixels(data.min.y, data.max.y);
    } catch (const std::exception& e) {
        return e.what();
    }
    return {};
}

std::string writeExrFile(const std::string& file, const ImageFile& image) {
    if (image.types.size() != image.channels.size() ||
        image.pixels.size() != image.window.area() * image.channels.size())
        return "image of " + std::to_string(image.channels.size()) + " channels has " +
               std::to_string(image.pixels.size()) + " values for its data window";
    if (image.window.empty()) return "image has an empty data window";
    try {
        useRenderThreads();
        const Imath::Box2i display({image.full_x, image.full_y},
                                   {image.full_x + image.full_width - 1, image.full_y + image.full_height - 1});
        const Imath::Box2i data({image.window.x0, image.window.y0}, {image.window.x1 - 1, image.window.y1 - 1});
        Imf::Header header(display, data);
        for (std::size_t c = 0; c < image.channels.size(); ++c)
            header.channels().insert(image.channels[c],
                                     Imf::Channel(image.types[c] == PixelType::Float ? Imf::FLOAT : Imf::HALF));
        for (const ImageAttribute& a : image.attributes)
            if (const std::string why = addAttribute(header, a); !why.empty()) return why;
        // OpenEXR writes the line-offset table when the file is destroyed and swallows errors there, so
        // the stream is ours: a full disk shows in its state after the close.
        std::ofstream os(file, std::ios::binary | std::ios::trunc);
        if (!os) return "cannot write " + file + ": cannot open it";
        {
            Imf::StdOFStream stream(os, file.c_str());
            Imf::OutputFile out(stream, header, Imf::globalThreadCount());
            std::vector<half> halves;
            out.setFrameBuffer(writeBuffer(data, image, halves));
            out.writePixels(image.window.height());
        }
        os.close();
        if (os.fail()) return "cannot write " + file + ": the file did not close cleanly (disk full?)";
    } catch (const std::exception& e) {
        return "cannot write " + file + ": " + e.what();
    }
    return {};
}

}  // namespace clipblur
