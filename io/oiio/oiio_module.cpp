// libclipblur_oiio.so: every use of OpenImageIO, behind renderer/image_module.h. Errors come back as
// text (no exception crosses the module's edge).
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>

#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include "renderer/image_module.h"
#include "renderer/shading/image_textures.h"

namespace clipblur {

static_assert(OIIO::TypeDesc::INT32 == kBaseInt32 && OIIO::TypeDesc::FLOAT == kBaseFloat &&
                  OIIO::TypeDesc::STRING == kBaseString && OIIO::TypeDesc::MATRIX44 == kTypeMatrix44.aggregate &&
                  OIIO::TypeDesc::RATIONAL == kTypeRational.semantics,
              "AttributeType mirrors OpenImageIO's TypeDesc numbering");

namespace {

OIIO::TypeDesc typeDesc(const AttributeType& t) {
    return OIIO::TypeDesc(OIIO::TypeDesc::BASETYPE(t.base), OIIO::TypeDesc::AGGREGATE(t.aggregate),
                          OIIO::TypeDesc::VECSEMANTICS(t.semantics), t.array);
}

OIIO::TypeDesc pixelType(PixelType t) {
    switch (t) {
        case PixelType::UInt8: return OIIO::TypeDesc::UINT8;
        case PixelType::Half: return OIIO::TypeDesc::HALF;
        case PixelType::Float: return OIIO::TypeDesc::FLOAT;
    }
    return OIIO::TypeDesc::FLOAT;
}

// Files of other writers may store other types; they are read as float all the same.
PixelType pixelType(OIIO::TypeDesc t) {
    if (t == OIIO::TypeDesc::UINT8) return PixelType::UInt8;
    if (t == OIIO::TypeDesc::HALF) return PixelType::Half;
    return PixelType::Float;
}

ImageAttribute attributeOf(const OIIO::ParamValue& p) {
    const OIIO::TypeDesc t = p.type();
    ImageAttribute a{p.name().string(), {t.basetype, t.aggregate, t.vecsemantics, t.arraylen}, {}, {}};
    if (t.basetype == OIIO::TypeDesc::STRING) {
        for (int i = 0; i < p.nvalues() * static_cast<int>(t.numelements()); ++i)
            a.text.emplace_back(p.get_ustring(i).string());
    } else {
        const auto* data = static_cast<const unsigned char*>(p.data());
        a.bytes.assign(data, data + t.size() * static_cast<std::size_t>(p.nvalues()));
    }
    return a;
}

void addAttribute(OIIO::ImageSpec& spec, const ImageAttribute& a) {
    const OIIO::TypeDesc t = typeDesc(a.type);
    if (a.type.base == kBaseString) {
        std::vector<OIIO::ustring> text;
        for (const std::string& s : a.text) text.emplace_back(s);
        if (!text.empty()) spec.attribute(a.name, t, text.data());
    } else if (a.bytes.size() == t.size()) {
        spec.attribute(a.name, t, a.bytes.data());
    }
}

ImageFile describe(const OIIO::ImageInput& in) {
    const OIIO::ImageSpec& spec = in.spec();
    ImageFile f;
    f.format = in.format_name();
    f.full_width = spec.full_width;
    f.full_height = spec.full_height;
    f.full_x = spec.full_x;
    f.full_y = spec.full_y;
    f.window = PixelBounds::sized(spec.x, spec.y, spec.width, spec.height);
    f.flat = spec.depth == 1 && spec.z == 0;
    f.channels = spec.channelnames;
    for (int c = 0; c < spec.nchannels; ++c) f.types.push_back(pixelType(spec.channelformat(c)));
    for (const OIIO::ParamValue& p : spec.extra_attribs) f.attributes.push_back(attributeOf(p));
    return f;
}

std::string readImage(const std::string& file, ImageRead what, ImageFile& out) {
    auto in = OIIO::ImageInput::open(file);
    out = ImageFile{};
    if (!in) return OIIO::geterror();
    out = describe(*in);
    if (what == ImageRead::Header) return {};
    const OIIO::ImageSpec& spec = in->spec();
    // Reading every pixel is the only reliable test for a file cut short: the header of a truncated EXR
    // is intact, its missing chunks only show when read.
    out.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.depth * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.pixels.data())) return in->geterror();
    return {};
}

OIIO::ImageSpec specOf(const ImageFile& image) {
    const int nc = static_cast<int>(image.channels.size());
    OIIO::ImageSpec spec(image.window.width(), image.window.height(), nc, OIIO::TypeDesc::FLOAT);
    spec.x = image.window.x0;
    spec.y = image.window.y0;
    spec.full_x = image.full_x;
    spec.full_y = image.full_y;
    spec.full_width = image.full_width;
    spec.full_height = image.full_height;
    spec.channelnames = image.channels;
    spec.channelformats.clear();
    spec.alpha_channel = spec.z_channel = -1;
    for (int c = 0; c < nc; ++c) {
        spec.channelformats.push_back(pixelType(image.types[static_cast<std::size_t>(c)]));
        if (image.channels[static_cast<std::size_t>(c)] == "A") spec.alpha_channel = c;
        if (image.channels[static_cast<std::size_t>(c)] == "Z") spec.z_channel = c;
    }
    // The format of the first channel (colour), which readers report as the image's.
    spec.format = nc > 0 ? spec.channelformats.front() : OIIO::TypeDesc::FLOAT;
    bool uniform = true;
    for (const OIIO::TypeDesc& t : spec.channelformats) uniform = uniform && t == spec.format;
    if (uniform) spec.channelformats.clear();
    for (const ImageAttribute& a : image.attributes) addAttribute(spec, a);
    return spec;
}

std::string writeImage(const std::string& file, const ImageFile& image) {
    if (image.types.size() != image.channels.size() ||
        image.pixels.size() != image.window.area() * image.channels.size())
        return "image of " + std::to_string(image.channels.size()) + " channels has " +
               std::to_string(image.pixels.size()) + " values for its data window";
    auto out = OIIO::ImageOutput::create(file);
    if (!out) return "cannot create a writer for " + file + ": " + OIIO::geterror();
    if (!out->open(file, specOf(image)) || !out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) ||
        !out->close())
        return "cannot write " + file + ": " + out->geterror();
    return {};
}

bool isFloat(OIIO::TypeDesc format) {
    return format.basetype == OIIO::TypeDesc::FLOAT || format.basetype == OIIO::TypeDesc::HALF ||
           format.basetype == OIIO::TypeDesc::DOUBLE;
}

// The image as linear float RGB: grey repeated, alpha dropped (the renderer has no cut-outs).
OIIO::ImageBuf linearRgb(OIIO::ImageBuf& source) {
    const OIIO::ImageSpec& in = source.spec();
    // The file's own texel type: the buffer itself was read as float.
    const bool srgb = !isFloat(source.nativespec().format);
    OIIO::ImageSpec spec(in.width, in.height, 3, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf out(spec);
    std::vector<float> pixel(static_cast<std::size_t>(in.nchannels));
    for (int y = 0; y < in.height; ++y) {
        for (int x = 0; x < in.width; ++x) {
            source.getpixel(in.x + x, in.y + y, pixel.data(), in.nchannels);
            float rgb[3];
            for (int c = 0; c < 3; ++c) {
                const float v = pixel[static_cast<std::size_t>(in.nchannels >= 3 ? c : 0)];
                rgb[c] = srgb ? static_cast<float>(srgbToLinear(v)) : v;
            }
            out.setpixel(x, y, rgb, 3);
        }
    }
    return out;
}

class OiioTextures final : public ImageTextures {
public:
    OiioTextures() {
        system_ = OIIO::TextureSystem::create(false);
        // Every texel of a scene's textures stays cached: no re-reads while rendering, and lookups do not
        // depend on which thread evicted what.
        system_->attribute("max_memory_MB", 4096.0f);
        system_->attribute("autotile", 64);
        folder_ = std::filesystem::temp_directory_path() / ("clipblur-textures-" + std::to_string(::getpid()));
    }

    const Image* find(const std::string& file) const override;
    glm::dvec3 lookup(const Image& image, const glm::dvec2& st, const TextureFootprint& footprint) const override;
    Texels texels(const Image& image) const override;
    void removePreparedFiles() {
        std::error_code ignored;
        std::filesystem::remove_all(folder_, ignored);
    }

protected:
    std::string load(const std::string& file) override;

private:
    OIIO::TextureSystem* system_ = nullptr;
    std::filesystem::path folder_;
    mutable std::mutex mutex_;
    std::map<std::string, std::unique_ptr<Image>> prepared_;  // by source file; entries never move or go
};

}  // namespace

struct ImageTextures::Image {
    OIIO::TextureSystem::TextureHandle* handle = nullptr;  // of the linear MIP-mapped copy
};

namespace {

std::string OiioTextures::load(const std::string& file) {
    const std::lock_guard lock(mutex_);
    if (prepared_.count(file)) return {};
    OIIO::ImageBuf source(file);
    if (!source.read(0, 0, true, OIIO::TypeDesc::FLOAT) || source.spec().width <= 0 || source.spec().height <= 0)
        return "cannot read texture file '" + file + "': " + source.geterror();
    const OIIO::ImageBuf linear = linearRgb(source);
    std::error_code ec;
    std::filesystem::create_directories(folder_, ec);
    const std::string copy = (folder_ / (std::to_string(prepared_.size()) + ".exr")).string();
    OIIO::ImageSpec config;
    config.attribute("maketx:filtername", "box");
    config.attribute("maketx:fixnan", "box3");
    config.tile_width = config.tile_height = 64;
    config.format = OIIO::TypeDesc::FLOAT;
    config.attribute("wrapmodes", "periodic,periodic");
    if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, linear, copy, config))
        return "cannot prepare texture file '" + file + "': " + OIIO::geterror();
    auto image = std::make_unique<Image>();
    image->handle = system_->get_texture_handle(OIIO::ustring(copy));
    if (!image->handle) return "cannot open the prepared copy of texture file '" + file + "'";
    prepared_.emplace(file, std::move(image));
    return {};
}

const ImageTextures::Image* OiioTextures::find(const std::string& file) const {
    const std::lock_guard lock(mutex_);
    const auto it = prepared_.find(file);
    return it == prepared_.end() ? nullptr : it->second.get();
}

glm::dvec3 OiioTextures::lookup(const Image& image, const glm::dvec2& st, const TextureFootprint& f) const {
    OIIO::TextureOpt options;
    options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
    // Bilinear between texel centres: the image function the stochastic reference point-samples, so that
    // its converged average is the area integral the filtered lookups approximate.
    options.interpmode = OIIO::TextureOpt::InterpBilinear;
    float rgb[3] = {0.0f, 0.0f, 0.0f};
    system_->texture(image.handle, system_->get_perthread_info(), options, static_cast<float>(st.x),
                     static_cast<float>(st.y), static_cast<float>(f.dx.x), static_cast<float>(f.dx.y),
                     static_cast<float>(f.dy.x), static_cast<float>(f.dy.y), 3, rgb);
    return glm::dvec3(rgb[0], rgb[1], rgb[2]);
}

ImageTextures::Texels OiioTextures::texels(const Image& image) const {
    Texels out;
    OIIO::TextureSystem::Perthread* thread = system_->get_perthread_info();
    const OIIO::ImageSpec* spec = system_->imagespec(image.handle, thread);
    if (!spec || spec->width <= 0 || spec->height <= 0) return out;
    out.width = spec->width;
    out.height = spec->height;
    out.rgb.resize(3 * static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
    OIIO::TextureOpt options;
    // The prepared copy is linear RGB (linearRgb), stored as float: these are the lookups' own texels.
    if (!system_->get_texels(image.handle, thread, options, 0, spec->x, spec->x + out.width, spec->y,
                             spec->y + out.height, 0, 1, 0, 3, OIIO::TypeDesc::FLOAT, out.rgb.data()))
        return {};
    return out;
}

ImageTextures& textures() {
    // Never destroyed: OpenImageIO 2.4's TextureSystem::destroy deletes the system through a pointer of
    // the wrong type (ASan: new-delete-type-mismatch inside libOpenImageIO), and the process ends here
    // anyway. Reachable from this static to its end, so it is no leak; only the prepared files go.
    static OiioTextures* const instance = [] {
        auto* t = new OiioTextures;
        std::atexit([] { static_cast<OiioTextures&>(textures()).removePreparedFiles(); });
        return t;
    }();
    return *instance;
}

}  // namespace

}  // namespace clipblur

extern "C" __attribute__((visibility("default"))) const clipblur::ImageModule* clipblur_image_module() {
    static const clipblur::ImageModule module{clipblur::readImage, clipblur::writeImage, clipblur::textures};
    return &module;
}
